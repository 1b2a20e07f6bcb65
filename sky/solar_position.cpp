// Reda and Andreas, NREL/TP-560-34302 (revised 2008): the Solar Position Algorithm, step by step.
// Equation and table numbers are the report's. Angles are in degrees unless a name says _rad.

#include "sky/solar_position.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <string>

#include <fmt/format.h>

#include "geometry/error.hpp"

namespace daylit {

namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr double kRadPerDeg = std::numbers::pi / 180.0;
constexpr double kSunRadiusDeg = 0.26667;  // report A.2

double sind(double deg) { return std::sin(deg * kRadPerDeg); }
double cosd(double deg) { return std::cos(deg * kRadPerDeg); }

// Step 3.2.6: an angle reduced to [0, 360).
double limit_360(double deg) {
  const double r = std::fmod(deg, 360.0);
  return r < 0 ? (r + 360.0 < 360.0 ? r + 360.0 : 0.0) : r;
}

// ---------------------------------------------------------------------------------------------
// Table A4.2: Earth periodic terms (VSOP87, truncated). Row i of series Ln contributes
// A_i cos(B_i + C_i·JME) (eq. 9), in 1e-8 rad (L, B) or 1e-8 AU (R).

struct PeriodicTerm {
  double a, b, c;
};

constexpr PeriodicTerm kL0[] = {
    {175347046, 0, 0},         {3341656, 4.6692568, 6283.07585}, {34894, 4.6261, 12566.1517},
    {3497, 2.7441, 5753.3849}, {3418, 2.8289, 3.5231},           {3136, 3.6277, 77713.7715},
    {2676, 4.4181, 7860.4194}, {2343, 6.1352, 3930.2097},        {1324, 0.7425, 11506.7698},
    {1273, 2.0371, 529.691},   {1199, 1.1096, 1577.3435},        {990, 5.233, 5884.927},
    {902, 2.045, 26.298},      {857, 3.508, 398.149},            {780, 1.179, 5223.694},
    {753, 2.533, 5507.553},    {505, 4.583, 18849.228},          {492, 4.205, 775.523},
    {357, 2.92, 0.067},        {317, 5.849, 11790.629},          {284, 1.899, 796.298},
    {271, 0.315, 10977.079},   {243, 0.345, 5486.778},           {206, 4.806, 2544.314},
    {205, 1.869, 5573.143},    {202, 2.458, 6069.777},           {156, 0.833, 213.299},
    {132, 3.411, 2942.463},    {126, 1.083, 20.775},             {115, 0.645, 0.98},
    {103, 0.636, 4694.003},    {102, 0.976, 15720.839},          {102, 4.267, 7.114},
    {99, 6.21, 2146.17},       {98, 0.68, 155.42},               {86, 5.98, 161000.69},
    {85, 1.3, 6275.96},        {85, 3.67, 71430.7},              {80, 1.81, 17260.15},
    {79, 3.04, 12036.46},      {75, 1.76, 5088.63},              {74, 3.5, 3154.69},
    {74, 4.68, 801.82},        {70, 0.83, 9437.76},              {62, 3.98, 8827.39},
    {61, 1.82, 7084.9},        {57, 2.78, 6286.6},               {56, 4.39, 14143.5},
    {56, 3.47, 6279.55},       {52, 0.19, 12139.55},             {52, 1.33, 1748.02},
    {51, 0.28, 5856.48},       {49, 0.49, 1194.45},              {41, 5.37, 8429.24},
    {41, 2.4, 19651.05},       {39, 6.17, 10447.39},             {37, 6.04, 10213.29},
    {37, 2.57, 1059.38},       {36, 1.71, 2352.87},              {36, 1.78, 6812.77},
    {33, 0.59, 17789.85},      {30, 0.44, 83996.85},             {30, 2.74, 1349.87},
    {25, 3.16, 4690.48},
};
constexpr PeriodicTerm kL1[] = {
    {628331966747, 0, 0}, {206059, 2.678235, 6283.07585}, {4303, 2.6351, 12566.1517},
    {425, 1.59, 3.523},   {119, 5.796, 26.298},           {109, 2.966, 1577.344},
    {93, 2.59, 18849.23}, {72, 1.14, 529.69},             {68, 1.87, 398.15},
    {67, 4.41, 5507.55},  {59, 2.89, 5223.69},            {56, 2.17, 155.42},
    {45, 0.4, 796.3},     {36, 0.47, 775.52},             {29, 2.65, 7.11},
    {21, 5.34, 0.98},     {19, 1.85, 5486.78},            {19, 4.97, 213.3},
    {17, 2.99, 6275.96},  {16, 0.03, 2544.31},            {16, 1.43, 2146.17},
    {15, 1.21, 10977.08}, {12, 2.83, 1748.02},            {12, 3.26, 5088.63},
    {12, 5.27, 1194.45},  {12, 2.08, 4694},               {11, 0.77, 553.57},
    {10, 1.3, 6286.6},    {10, 4.24, 1349.87},            {9, 2.7, 242.73},
    {9, 5.64, 951.72},    {8, 5.3, 2352.87},              {6, 2.65, 9437.76},
    {6, 4.67, 4690.48},
};
constexpr PeriodicTerm kL2[] = {
    {52919, 0, 0},       {8720, 1.0721, 6283.0758}, {309, 0.867, 12566.152}, {27, 0.05, 3.52},
    {16, 5.19, 26.3},    {16, 3.68, 155.42},        {10, 0.76, 18849.23},    {9, 2.06, 77713.77},
    {7, 0.83, 775.52},   {5, 4.66, 1577.34},        {4, 1.03, 7.11},         {4, 3.44, 5573.14},
    {3, 5.14, 796.3},    {3, 6.05, 5507.55},        {3, 1.19, 242.73},       {3, 6.12, 529.69},
    {3, 0.31, 398.15},   {3, 2.28, 553.57},         {2, 4.38, 5223.69},      {2, 3.75, 0.98},
};
constexpr PeriodicTerm kL3[] = {
    {289, 5.844, 6283.076}, {35, 0, 0},          {17, 5.49, 12566.15}, {3, 5.2, 155.42},
    {1, 4.72, 3.52},        {1, 5.3, 18849.23},  {1, 5.97, 242.73},
};
constexpr PeriodicTerm kL4[] = {{114, 3.142, 0}, {8, 4.13, 6283.08}, {1, 3.84, 12566.15}};
constexpr PeriodicTerm kL5[] = {{1, 3.14, 0}};

constexpr PeriodicTerm kB0[] = {
    {280, 3.199, 84334.662}, {102, 5.422, 5507.553}, {80, 3.88, 5223.69},
    {44, 3.7, 2352.87},      {32, 4, 1577.34},
};
constexpr PeriodicTerm kB1[] = {{9, 3.9, 5507.55}, {6, 1.73, 5223.69}};

constexpr PeriodicTerm kR0[] = {
    {100013989, 0, 0},         {1670700, 3.0984635, 6283.07585}, {13956, 3.05525, 12566.1517},
    {3084, 5.1985, 77713.7715}, {1628, 1.1739, 5753.3849},       {1576, 2.8469, 7860.4194},
    {925, 5.453, 11506.77},    {542, 4.564, 3930.21},            {472, 3.661, 5884.927},
    {346, 0.964, 5507.553},    {329, 5.9, 5223.694},             {307, 0.299, 5573.143},
    {243, 4.273, 11790.629},   {212, 5.847, 1577.344},           {186, 5.022, 10977.079},
    {175, 3.012, 18849.228},   {110, 5.055, 5486.778},           {98, 0.89, 6069.78},
    {86, 5.69, 15720.84},      {86, 1.27, 161000.69},            {65, 0.27, 17260.15},
    {63, 0.92, 529.69},        {57, 2.01, 83996.85},             {56, 5.24, 71430.7},
    {49, 3.25, 2544.31},       {47, 2.58, 775.52},               {45, 5.54, 9437.76},
    {43, 6.01, 6275.96},       {39, 5.36, 4694},                 {38, 2.39, 8827.39},
    {37, 0.83, 19651.05},      {37, 4.9, 12139.55},              {36, 1.67, 12036.46},
    {35, 1.84, 2942.46},       {33, 0.24, 7084.9},               {32, 0.18, 5088.63},
    {32, 1.78, 398.15},        {28, 1.21, 6286.6},               {28, 1.9, 6279.55},
    {26, 4.59, 10447.39},
};
constexpr PeriodicTerm kR1[] = {
    {103019, 1.10749, 6283.07585}, {1721, 1.0644, 12566.1517}, {702, 3.142, 0},
    {32, 1.02, 18849.23},          {31, 2.84, 5507.55},        {25, 1.32, 5223.69},
    {18, 1.42, 1577.34},           {10, 5.91, 10977.08},       {9, 1.42, 6275.96},
    {9, 0.27, 5486.78},
};
constexpr PeriodicTerm kR2[] = {
    {4359, 5.7846, 6283.0758}, {124, 5.579, 12566.152}, {12, 3.14, 0},
    {9, 3.63, 77713.77},       {6, 1.87, 5573.14},      {3, 5.47, 18849.23},
};
constexpr PeriodicTerm kR3[] = {{145, 4.273, 6283.076}, {7, 3.92, 12566.15}};
constexpr PeriodicTerm kR4[] = {{4, 2.56, 6283.08}};

// Eqs. 9–10: one series summed, smallest terms first (the table lists them largest first).
double series_sum(std::span<const PeriodicTerm> terms, double jme) {
  double sum = 0;
  for (auto t = terms.rbegin(); t != terms.rend(); ++t) sum += t->a * std::cos(t->b + t->c * jme);
  return sum;
}

// Eq. 11 (and its B and R versions, steps 3.2.7–3.2.8): Σ_n S_n·JME^n / 1e8, by Horner's rule.
template <std::size_t N>
double power_series(const std::array<double, N>& s, double jme) {
  double v = 0;
  for (std::size_t n = N; n-- > 0;) v = v * jme + s[n];
  return v / 1e8;
}

// ---------------------------------------------------------------------------------------------
// Table A4.3: periodic terms for the nutation in longitude and obliquity (the 63 terms of the
// IAU 1980 theory that Meeus's Table 22.A keeps). Row i: multiples Y_i,0…4 of X0…X4, and
// coefficients a, b (Δψ) and c, d (Δε) in 0.0001″ (eqs. 20–21).

struct NutationTerm {
  std::int8_t y[5];
  double a, b, c, d;
};

constexpr NutationTerm kNutation[] = {
    {{0, 0, 0, 0, 1}, -171996, -174.2, 92025, 8.9},
    {{-2, 0, 0, 2, 2}, -13187, -1.6, 5736, -3.1},
    {{0, 0, 0, 2, 2}, -2274, -0.2, 977, -0.5},
    {{0, 0, 0, 0, 2}, 2062, 0.2, -895, 0.5},
    {{0, 1, 0, 0, 0}, 1426, -3.4, 54, -0.1},
    {{0, 0, 1, 0, 0}, 712, 0.1, -7, 0},
    {{-2, 1, 0, 2, 2}, -517, 1.2, 224, -0.6},
    {{0, 0, 0, 2, 1}, -386, -0.4, 200, 0},
    {{0, 0, 1, 2, 2}, -301, 0, 129, -0.1},
    {{-2, -1, 0, 2, 2}, 217, -0.5, -95, 0.3},
    {{-2, 0, 1, 0, 0}, -158, 0, 0, 0},
    {{-2, 0, 0, 2, 1}, 129, 0.1, -70, 0},
    {{0, 0, -1, 2, 2}, 123, 0, -53, 0},
    {{2, 0, 0, 0, 0}, 63, 0, 0, 0},
    {{0, 0, 1, 0, 1}, 63, 0.1, -33, 0},
    {{2, 0, -1, 2, 2}, -59, 0, 26, 0},
    {{0, 0, -1, 0, 1}, -58, -0.1, 32, 0},
    {{0, 0, 1, 2, 1}, -51, 0, 27, 0},
    {{-2, 0, 2, 0, 0}, 48, 0, 0, 0},
    {{0, 0, -2, 2, 1}, 46, 0, -24, 0},
    {{2, 0, 0, 2, 2}, -38, 0, 16, 0},
    {{0, 0, 2, 2, 2}, -31, 0, 13, 0},
    {{0, 0, 2, 0, 0}, 29, 0, 0, 0},
    {{-2, 0, 1, 2, 2}, 29, 0, -12, 0},
    {{0, 0, 0, 2, 0}, 26, 0, 0, 0},
    {{-2, 0, 0, 2, 0}, -22, 0, 0, 0},
    {{0, 0, -1, 2, 1}, 21, 0, -10, 0},
    {{0, 2, 0, 0, 0}, 17, -0.1, 0, 0},
    {{2, 0, -1, 0, 1}, 16, 0, -8, 0},
    {{-2, 2, 0, 2, 2}, -16, 0.1, 7, 0},
    {{0, 1, 0, 0, 1}, -15, 0, 9, 0},
    {{-2, 0, 1, 0, 1}, -13, 0, 7, 0},
    {{0, -1, 0, 0, 1}, -12, 0, 6, 0},
    {{0, 0, 2, -2, 0}, 11, 0, 0, 0},
    {{2, 0, -1, 2, 1}, -10, 0, 5, 0},
    {{2, 0, 1, 2, 2}, -8, 0, 3, 0},
    {{0, 1, 0, 2, 2}, 7, 0, -3, 0},
    {{-2, 1, 1, 0, 0}, -7, 0, 0, 0},
    {{0, -1, 0, 2, 2}, -7, 0, 3, 0},
    {{2, 0, 0, 2, 1}, -7, 0, 3, 0},
    {{2, 0, 1, 0, 0}, 6, 0, 0, 0},
    {{-2, 0, 2, 2, 2}, 6, 0, -3, 0},
    {{-2, 0, 1, 2, 1}, 6, 0, -3, 0},
    {{2, 0, -2, 0, 1}, -6, 0, 3, 0},
    {{2, 0, 0, 0, 1}, -6, 0, 3, 0},
    {{0, -1, 1, 0, 0}, 5, 0, 0, 0},
    {{-2, -1, 0, 2, 1}, -5, 0, 3, 0},
    {{-2, 0, 0, 0, 1}, -5, 0, 3, 0},
    {{0, 0, 2, 2, 1}, -5, 0, 3, 0},
    {{-2, 0, 2, 0, 1}, 4, 0, 0, 0},
    {{-2, 1, 0, 2, 1}, 4, 0, 0, 0},
    {{0, 0, 1, -2, 0}, 4, 0, 0, 0},
    {{-1, 0, 1, 0, 0}, -4, 0, 0, 0},
    {{-2, 1, 0, 0, 0}, -4, 0, 0, 0},
    {{1, 0, 0, 0, 0}, -4, 0, 0, 0},
    {{0, 0, 1, 2, 0}, 3, 0, 0, 0},
    {{0, 0, -2, 2, 2}, -3, 0, 0, 0},
    {{-1, -1, 1, 0, 0}, -3, 0, 0, 0},
    {{0, 1, 1, 0, 0}, -3, 0, 0, 0},
    {{0, -1, 1, 2, 2}, -3, 0, 0, 0},
    {{2, -1, -1, 2, 2}, -3, 0, 0, 0},
    {{0, 0, 3, 2, 2}, -3, 0, 0, 0},
    {{2, -1, 0, 2, 2}, -3, 0, 0, 0},
};
static_assert(std::size(kNutation) == 63);

// Horner's rule for c0 + c1 x + c2 x² + …
template <std::size_t N>
double polynomial(const double (&c)[N], double x) {
  double v = 0;
  for (std::size_t n = N; n-- > 0;) v = v * x + c[n];
  return v;
}

// ---------------------------------------------------------------------------------------------
// Calendar.

bool is_julian_calendar(int year, int month, int day) {
  return year < 1582 || (year == 1582 && (month < 10 || (month == 10 && day < 15)));
}

bool is_leap_year(int year, bool julian) {
  const bool by4 = year % 4 == 0;  // also right for negative years: −1000 % 4 == 0
  return julian ? by4 : by4 && (year % 100 != 0 || year % 400 == 0);
}

int days_in_month(int year, int month) {
  static constexpr int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (month == 2 && is_leap_year(year, is_julian_calendar(year, month, 1))) return 29;
  return kDays[month - 1];
}

// Eq. 4 at 0 h of the date, plus 0.5: the integer Julian Day Number of noon on that date. The
// report's INT truncates toward zero; Y + 4716 > 0 for every year accepted, so floor is the same.
long julian_day_number(int year, int month, int day) {
  const bool julian = is_julian_calendar(year, month, day);
  long y = year, m = month;
  if (m <= 2) {
    y -= 1;
    m += 12;
  }
  // 365.25·(Y + 4716) is exact in binary; 30.6001 rather than 30.6 keeps INT off rounding errors.
  long jdn = long(std::floor(365.25 * double(y + 4716))) + long(std::floor(30.6001 * double(m + 1))) + day - 1524;
  if (!julian) {
    const long a = y / 100;  // C++ truncates toward zero, as INT does; y ≥ 1582 here anyway
    jdn += 2 - a + a / 4;
  }
  return jdn;
}

// Days from J2000.0 (JD 2451545.0 = 2000-01-01 12:00) to the instant t in UTC plus extra_s
// seconds, kept precise: the offset is removed in whole minutes and the day carried into the
// integer day number, so one instant written in any offset gives the same double.
double days_from_j2000(const CivilTime& t, double extra_s) {
  const long minutes = long(t.hour) * 60 + t.minute - t.utc_offset_min;
  const long day_shift = minutes >= 0 ? minutes / 1440 : -((-minutes + 1439) / 1440);
  const long minute_of_day = minutes - day_shift * 1440;
  const long jdn = julian_day_number(t.year, t.month, t.day) + day_shift;
  const double seconds_from_noon = double(minute_of_day * 60 - 43200) + t.second + extra_s;
  return double(jdn - 2451545) + seconds_from_noon / 86400.0;
}

// ---------------------------------------------------------------------------------------------
// Validation at the boundary (STYLE.md habit 5).

// Throws daylit::Error with the message unless ok (formatted only then).
template <class... Args>
void require(bool ok, fmt::format_string<Args...> message, Args&&... args) {
  if (!ok) throw Error(fmt::format(message, std::forward<Args>(args)...));
}

bool finite(double v) { return std::isfinite(v); }

void check_input(const SolarPositionInput& in) {
  check_civil_time(in.time);
  require(finite(in.delta_ut1_s) && std::abs(in.delta_ut1_s) <= 1, "UT1 - UTC = {} s is not within [-1, 1] s",
          in.delta_ut1_s);
  if (in.delta_t_s)
    require(finite(*in.delta_t_s) && std::abs(*in.delta_t_s) <= 1e5, "Delta T = {} s is not within [-1e5, 1e5] s",
            *in.delta_t_s);
  require(finite(in.latitude_deg) && std::abs(in.latitude_deg) <= 90, "latitude {} is not within [-90, 90] degrees",
          in.latitude_deg);
  require(finite(in.longitude_deg) && std::abs(in.longitude_deg) <= 180,
          "longitude {} is not within [-180, 180] degrees", in.longitude_deg);
  require(finite(in.elevation_m) && in.elevation_m > -6378140, "elevation {} m is below the centre of the Earth",
          in.elevation_m);
  require(finite(in.pressure_hpa) && in.pressure_hpa >= 0 && in.pressure_hpa <= 5000,
          "pressure {} hPa is not within [0, 5000] hPa", in.pressure_hpa);
  require(finite(in.temperature_c) && in.temperature_c > -273 && in.temperature_c <= 6000,
          "temperature {} degrees C is not within (-273, 6000]", in.temperature_c);
  require(finite(in.refraction_at_sunrise_deg) && in.refraction_at_sunrise_deg >= 0 &&
              in.refraction_at_sunrise_deg <= 2,
          "refraction at sunrise {} is not within [0, 2] degrees", in.refraction_at_sunrise_deg);
}

}  // namespace

// ---------------------------------------------------------------------------------------------

void check_civil_time(const CivilTime& t) {
  require(t.year >= -2000 && t.year <= 6000, "year {} is outside the algorithm's range, -2000 to 6000", t.year);
  require(t.month >= 1 && t.month <= 12, "month {} is not within 1-12", t.month);
  require(t.day >= 1 && t.day <= days_in_month(t.year, t.month), "day {} does not exist in {:04}-{:02}", t.day,
          t.year, t.month);
  require(!(t.year == 1582 && t.month == 10 && t.day > 4 && t.day < 15),
          "1582-10-{:02} does not exist: the Gregorian calendar follows 1582-10-04 with 1582-10-15", t.day);
  require(t.hour >= 0 && t.hour <= 24, "hour {} is not within 0-24", t.hour);
  require(t.minute >= 0 && t.minute <= 59, "minute {} is not within 0-59", t.minute);
  require(finite(t.second) && t.second >= 0 && t.second < 61, "second {} is not within [0, 60)", t.second);
  require(t.hour < 24 || (t.minute == 0 && t.second == 0), "hour 24 is only allowed as 24:00:00");
  require(std::abs(t.utc_offset_min) <= 18 * 60, "UTC offset {} min is not within +-18 h", t.utc_offset_min);
  if (t.second >= 60) {
    // A leap second is 23:59:60 UTC, whatever the offset the time is written in.
    const int minute_utc = ((t.hour * 60 + t.minute - t.utc_offset_min) % 1440 + 1440) % 1440;
    require(minute_utc == 1439, "second {} is only allowed in a leap second, 23:59:60 UTC", t.second);
  }
}

double julian_day(const CivilTime& t) {
  check_civil_time(t);
  return 2451545.0 + days_from_j2000(t, 0);
}

double delta_t_espenak_meeus(double y) noexcept {
  // Espenak and Meeus, NASA/TP-2006-214141, §2.6 (eclipse.gsfc.nasa.gov/SEhelp/deltatpoly2004).
  if (y < -500) {
    const double u = (y - 1820) / 100;
    return -20 + 32 * u * u;
  }
  if (y < 500) {
    static constexpr double c[] = {10583.6, -1014.41, 33.78311, -5.952053, -0.1798452, 0.022174192, 0.0090316521};
    return polynomial(c, y / 100);
  }
  if (y < 1600) {
    static constexpr double c[] = {1574.2, -556.01, 71.23472, 0.319781, -0.8503463, -0.005050998, 0.0083572073};
    return polynomial(c, (y - 1000) / 100);
  }
  if (y < 1700) {
    static constexpr double c[] = {120, -0.9808, -0.01532, 1.0 / 7129};
    return polynomial(c, y - 1600);
  }
  if (y < 1800) {
    static constexpr double c[] = {8.83, 0.1603, -0.0059285, 0.00013336, -1.0 / 1174000};
    return polynomial(c, y - 1700);
  }
  if (y < 1860) {
    static constexpr double c[] = {13.72,        -0.332447,     0.0068612,     0.0041116,
                                   -0.00037436,  0.0000121272,  -0.0000001699, 0.000000000875};
    return polynomial(c, y - 1800);
  }
  if (y < 1900) {
    static constexpr double c[] = {7.62, 0.5737, -0.251754, 0.01680668, -0.0004473624, 1.0 / 233174};
    return polynomial(c, y - 1860);
  }
  if (y < 1920) {
    static constexpr double c[] = {-2.79, 1.494119, -0.0598939, 0.0061966, -0.000197};
    return polynomial(c, y - 1900);
  }
  if (y < 1941) {
    static constexpr double c[] = {21.20, 0.84493, -0.076100, 0.0020936};
    return polynomial(c, y - 1920);
  }
  if (y < 1961) {
    static constexpr double c[] = {29.07, 0.407, -1.0 / 233, 1.0 / 2547};
    return polynomial(c, y - 1950);
  }
  if (y < 1986) {
    static constexpr double c[] = {45.45, 1.067, -1.0 / 260, -1.0 / 718};
    return polynomial(c, y - 1975);
  }
  if (y < 2005) {
    static constexpr double c[] = {63.86, 0.3345, -0.060374, 0.0017275, 0.000651814, 0.00002373599};
    return polynomial(c, y - 2000);
  }
  if (y < 2050) {
    static constexpr double c[] = {62.92, 0.32217, 0.005589};
    return polynomial(c, y - 2000);
  }
  const double u = (y - 1820) / 100;
  if (y < 2150) return -20 + 32 * u * u - 0.5628 * (2150 - y);
  return -20 + 32 * u * u;
}

SolarPosition solar_position(const SolarPositionInput& in) {
  check_input(in);
  SpaSteps s;

  // §3.1: Julian and Julian Ephemeris Day, century, millennium (eqs. 4–8), as days from J2000.0
  // so that no digits are lost to the 2.45e6 of the Julian Day.
  const double days_ut = days_from_j2000(in.time, in.delta_ut1_s);
  // Espenak–Meeus at the decimal year of the instant (Gregorian years of 365.2425 days from
  // 2000-01-01 0 h), continuous where their year + (month − 0.5)/12 steps.
  s.delta_t_s = in.delta_t_s ? *in.delta_t_s : delta_t_espenak_meeus(2000.0 + (days_ut + 0.5) / 365.2425);
  const double days_tt = days_ut + s.delta_t_s / 86400.0;  // eq. 5
  s.jd = 2451545.0 + days_ut;
  s.jde = 2451545.0 + days_tt;
  s.jc = days_ut / 36525.0;   // eq. 6
  s.jce = days_tt / 36525.0;  // eq. 7
  s.jme = s.jce / 10.0;       // eq. 8
  const double jme = s.jme, jce = s.jce, jc = s.jc;

  // §3.2: Earth heliocentric longitude, latitude and radius vector (eqs. 9–12, Table A4.2).
  s.l_terms = {series_sum(kL0, jme), series_sum(kL1, jme), series_sum(kL2, jme),
               series_sum(kL3, jme), series_sum(kL4, jme), series_sum(kL5, jme)};
  s.b_terms = {series_sum(kB0, jme), series_sum(kB1, jme)};
  s.r_terms = {series_sum(kR0, jme), series_sum(kR1, jme), series_sum(kR2, jme), series_sum(kR3, jme),
               series_sum(kR4, jme)};
  s.l_deg = limit_360(power_series(s.l_terms, jme) * kDegPerRad);
  s.b_deg = power_series(s.b_terms, jme) * kDegPerRad;
  s.r_au = power_series(s.r_terms, jme);

  // §3.3: geocentric longitude and latitude (eqs. 13–14).
  s.theta_deg = limit_360(s.l_deg + 180.0);
  s.beta_deg = -s.b_deg;

  // §3.4: nutation in longitude and obliquity (eqs. 15–23, Table A4.3).
  {
    static constexpr double x0[] = {297.85036, 445267.111480, -0.0019142, 1.0 / 189474};
    static constexpr double x1[] = {357.52772, 35999.050340, -0.0001603, -1.0 / 300000};
    static constexpr double x2[] = {134.96298, 477198.867398, 0.0086972, 1.0 / 56250};
    static constexpr double x3[] = {93.27191, 483202.017538, -0.0036825, 1.0 / 327270};
    static constexpr double x4[] = {125.04452, -1934.136261, 0.0020708, 1.0 / 450000};
    s.x_deg = {polynomial(x0, jce), polynomial(x1, jce), polynomial(x2, jce), polynomial(x3, jce),
               polynomial(x4, jce)};
    double x_rad[5];
    for (int j = 0; j < 5; ++j) x_rad[j] = limit_360(s.x_deg[j]) * kRadPerDeg;
    double sum_psi = 0, sum_eps = 0;
    for (auto t = std::rbegin(kNutation); t != std::rend(kNutation); ++t) {
      double arg = 0;
      for (int j = 0; j < 5; ++j) arg += x_rad[j] * t->y[j];
      sum_psi += (t->a + t->b * jce) * std::sin(arg);  // eq. 20
      sum_eps += (t->c + t->d * jce) * std::cos(arg);  // eq. 21
    }
    s.delta_psi_deg = sum_psi / 36000000.0;      // eq. 22
    s.delta_epsilon_deg = sum_eps / 36000000.0;  // eq. 23
  }

  // §3.5: true obliquity of the ecliptic (eqs. 24–25; Laskar's polynomial, Meeus eq. 22.3).
  {
    static constexpr double e0[] = {84381.448, -4680.93, -1.55, 1999.25, -51.38, -249.67,
                                    -39.05,    7.12,     27.87, 5.79,    2.45};
    s.epsilon0_arcsec = polynomial(e0, jme / 10.0);
    s.epsilon_deg = s.epsilon0_arcsec / 3600.0 + s.delta_epsilon_deg;
  }

  // §3.6–3.7: aberration and the apparent sun longitude (eqs. 26–27).
  s.delta_tau_deg = -20.4898 / (3600.0 * s.r_au);
  s.lambda_deg = s.theta_deg + s.delta_psi_deg + s.delta_tau_deg;

  // §3.8: apparent sidereal time at Greenwich (eqs. 28–29). With d = n + f (n whole days),
  // 360.98564736629·d ≡ 0.98564736629·n + 360.98564736629·f (mod 360): no 1e5–1e8 degrees to
  // round before the reduction, whatever the epoch.
  {
    const double n = std::floor(days_ut), f = days_ut - n;
    s.nu0_deg = limit_360(280.46061837 + limit_360(0.98564736629 * n) + 360.98564736629 * f +
                          0.000387933 * jc * jc - jc * jc * jc / 38710000.0);
  }
  s.nu_deg = s.nu0_deg + s.delta_psi_deg * cosd(s.epsilon_deg);

  // §3.9–3.10: geocentric right ascension and declination (eqs. 30–31).
  const double sin_lambda = sind(s.lambda_deg), cos_lambda = cosd(s.lambda_deg);
  const double sin_eps = sind(s.epsilon_deg), cos_eps = cosd(s.epsilon_deg);
  const double sin_beta = sind(s.beta_deg), cos_beta = cosd(s.beta_deg);
  s.alpha_deg = limit_360(
      std::atan2(sin_lambda * cos_eps - (sin_beta / cos_beta) * sin_eps, cos_lambda) * kDegPerRad);
  s.delta_deg = std::asin(sin_beta * cos_eps + cos_beta * sin_eps * sin_lambda) * kDegPerRad;

  // §3.11: observer local hour angle, westward from south (eq. 32).
  s.h_deg = limit_360(s.nu_deg + in.longitude_deg - s.alpha_deg);

  // §3.12–3.13: parallax; topocentric right ascension, declination, hour angle (eqs. 33–40).
  s.xi_deg = 8.794 / (3600.0 * s.r_au);
  const double phi = in.latitude_deg;
  const double sin_phi = sind(phi), cos_phi = cosd(phi);
  constexpr double kOneMinusF = 0.99664719;   // 1 − f of the report's Earth (eq. 34)
  constexpr double kEquatorialRadiusM = 6378140;
  // Eq. 34 as atan2(0.99664719 sin φ, cos φ): the same angle, defined at the poles too.
  const double u = std::atan2(kOneMinusF * sin_phi, cos_phi);
  const double x = std::cos(u) + in.elevation_m / kEquatorialRadiusM * cos_phi;               // eq. 35
  const double y = kOneMinusF * std::sin(u) + in.elevation_m / kEquatorialRadiusM * sin_phi;  // eq. 36
  const double sin_xi = sind(s.xi_deg);
  const double sin_h = sind(s.h_deg), cos_h = cosd(s.h_deg);
  const double sin_delta = sind(s.delta_deg), cos_delta = cosd(s.delta_deg);
  const double denominator = cos_delta - x * sin_xi * cos_h;
  const double delta_alpha_rad = std::atan2(-x * sin_xi * sin_h, denominator);  // eq. 37
  s.delta_alpha_deg = delta_alpha_rad * kDegPerRad;
  s.alpha_prime_deg = s.alpha_deg + s.delta_alpha_deg;  // eq. 38
  s.delta_prime_deg =
      std::atan2((sin_delta - y * sin_xi) * std::cos(delta_alpha_rad), denominator) * kDegPerRad;  // eq. 39
  s.h_prime_deg = s.h_deg - s.delta_alpha_deg;  // eq. 40

  // §3.14: topocentric elevation and zenith angle, with refraction (eqs. 41–44).
  const double sin_dp = sind(s.delta_prime_deg), cos_dp = cosd(s.delta_prime_deg);
  const double sin_hp = sind(s.h_prime_deg), cos_hp = cosd(s.h_prime_deg);
  s.e0_deg = std::asin(sin_phi * sin_dp + cos_phi * cos_dp * cos_hp) * kDegPerRad;
  // Eq. 42 holds while the sun is up; "up" as in NREL's spa.c: the upper limb above the horizon
  // that refraction at sunrise makes apparent, e0 ≥ −(0.26667° + 0.5667°) by default.
  if (s.e0_deg >= -(kSunRadiusDeg + in.refraction_at_sunrise_deg))
    s.delta_e_deg = (in.pressure_hpa / 1010.0) * (283.0 / (273.0 + in.temperature_c)) * 1.02 /
                    (60.0 * std::tan((s.e0_deg + 10.3 / (s.e0_deg + 5.11)) * kRadPerDeg));
  s.e_deg = s.e0_deg + s.delta_e_deg;
  s.zenith_deg = 90.0 - s.e_deg;

  // §3.15: azimuth (eqs. 45–46).
  s.gamma_deg = limit_360(std::atan2(sin_hp, cos_hp * sin_phi - (sin_dp / cos_dp) * cos_phi) * kDegPerRad);
  s.azimuth_deg = limit_360(s.gamma_deg + 180.0);

  // A.1: equation of time (eqs. A1–A2), limited to ±20 minutes by a whole day.
  {
    static constexpr double m[] = {280.4664567, 360007.6982779, 0.03032028, 1.0 / 49931, -1.0 / 15300,
                                   -1.0 / 2000000};
    s.m_deg = limit_360(polynomial(m, jme));
    double e_min = 4.0 * (s.m_deg - 0.0057183 - s.alpha_deg + s.delta_psi_deg * cosd(s.epsilon_deg));
    if (e_min < -20.0) e_min += 1440.0;
    if (e_min > 20.0) e_min -= 1440.0;
    s.equation_of_time_min = e_min;
  }

  SolarPosition p;
  p.zenith_deg = s.zenith_deg;
  p.azimuth_deg = s.azimuth_deg;
  p.elevation_deg = s.e_deg;
  p.declination_deg = s.delta_prime_deg;
  p.hour_angle_deg = limit_360(s.h_prime_deg);
  p.distance_au = s.r_au;
  p.equation_of_time_min = s.equation_of_time_min;
  p.steps = s;
  return p;
}

// ---------------------------------------------------------------------------------------------
// ISO 8601 parsing.

namespace {

class IsoScanner {
 public:
  explicit IsoScanner(std::string_view text) : text_(text) {}

  // A syntax error: says what was expected.
  [[noreturn]] void fail(const std::string& problem) const {
    throw Error(fmt::format("time \"{}\": {} (expected YYYY-MM-DDThh:mm:ss with Z or +hh:mm, e.g. "
                            "2003-10-17T12:30:30-07:00)",
                            text_, problem));
  }
  // A well-formed time that does not exist or is out of range.
  [[noreturn]] void refuse(const std::string& problem) const {
    throw Error(fmt::format("time \"{}\": {}", text_, problem));
  }
  bool at_end() const { return pos_ == text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }

  // Exactly n digits, named `what` in the message.
  int digits(int n, const char* what) {
    int v = 0;
    for (int i = 0; i < n; ++i) {
      if (at_end() || !std::isdigit(static_cast<unsigned char>(text_[pos_])))
        fail(fmt::format("the {} needs {} digits", what, n));
      v = v * 10 + (text_[pos_++] - '0');
    }
    return v;
  }
  void expect(char c, const char* where) {
    if (peek() != c) fail(fmt::format("'{}' expected {}", c, where));
    ++pos_;
  }
  bool accept(char c) {
    if (peek() != c) return false;
    ++pos_;
    return true;
  }
  // The digits after a decimal mark, as a fraction in [0, 1), correctly rounded (from_chars:
  // no locale).
  double fraction() {
    const std::size_t start = pos_;
    while (!at_end() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    if (pos_ == start) fail("digits expected after the decimal mark");
    const std::string digits = "0." + std::string(text_.substr(start, pos_ - start));
    double v = 0;
    std::from_chars(digits.data(), digits.data() + digits.size(), v);
    return v;
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
};

}  // namespace

CivilTime parse_iso8601_time(std::string_view text) {
  IsoScanner in(text);
  CivilTime t;
  t.year = in.digits(4, "year");
  in.expect('-', "after the year");
  t.month = in.digits(2, "month");
  in.expect('-', "after the month");
  t.day = in.digits(2, "day");
  if (!(in.accept('T') || in.accept('t') || in.accept(' '))) in.fail("'T' expected between the date and the time");
  t.hour = in.digits(2, "hour");
  in.expect(':', "after the hour");
  t.minute = in.digits(2, "minute");
  if (in.accept(':')) {
    t.second = in.digits(2, "second");
    if (in.accept('.') || in.accept(',')) t.second += in.fraction();
  }
  if (in.accept('Z') || in.accept('z')) {
    t.utc_offset_min = 0;
  } else if (in.peek() == '+' || in.peek() == '-') {
    const int sign = in.peek() == '-' ? -1 : 1;
    in.accept(in.peek());
    const int hh = in.digits(2, "offset hour");
    int mm = 0;
    if (in.accept(':')) {
      mm = in.digits(2, "offset minute");
    } else if (!in.at_end()) {
      mm = in.digits(2, "offset minute");
    }
    if (mm > 59) in.refuse(fmt::format("offset minute {} is not within 0-59", mm));
    if (hh * 60 + mm > 18 * 60) in.refuse("the UTC offset is not within +-18:00");
    t.utc_offset_min = sign * (hh * 60 + mm);
  } else {
    in.fail(in.at_end() ? "a UTC offset (Z or +hh:mm) is required: a time without one names no instant"
                        : "a UTC offset (Z or +hh:mm) expected after the time");
  }
  if (!in.at_end()) in.fail("unexpected text after the UTC offset");
  if (is_julian_calendar(t.year, t.month, t.day)) in.refuse("ISO 8601 dates are Gregorian and start at 1582-10-15");
  try {
    check_civil_time(t);
  } catch (const Error& e) {
    in.refuse(e.what());
  }
  return t;
}

}  // namespace daylit
