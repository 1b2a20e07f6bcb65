#pragma once
// The sun's position seen from a site on the Earth: the Solar Position Algorithm of Reda and
// Andreas, "Solar Position Algorithm for Solar Radiation Applications", NREL/TP-560-34302 (2004,
// revised January 2008), itself Meeus, "Astronomical Algorithms" (2nd ed., 1998), chapters 22–25,
// with the VSOP87 Earth series truncated as in the report's Table A4.2. Stated uncertainty
// ±0.0003° in zenith and azimuth for the years −2000 to 6000 (report §4: against the Astronomical
// Almanac, at most 0.00003° in zenith and 0.00008° in azimuth), given the right ΔT and UT1 − UTC.
// Equation numbers (eq. N) below and in solar_position.cpp are the report's.

#include <array>
#include <optional>
#include <string_view>

namespace daylit {

// A civil date and time of day with its offset from UTC, as written in ISO 8601:
// 2003-10-17T12:30:30-07:00 is {2003, 10, 17, 12, 30, 30.0, -420}. Dates from 1582-10-15 on are
// Gregorian; earlier ones are Julian, as in the report's eq. 4 (1582-10-05 to 14 do not exist).
struct CivilTime {
  int year = 2000;
  int month = 1;            // 1–12
  int day = 1;              // 1–length of the month
  int hour = 0;             // 0–23; 24 only for 24:00:00, the end of the day (ISO 8601)
  int minute = 0;           // 0–59
  double second = 0;        // [0, 60); [60, 61) only in a leap second, 23:59:60 UTC
  int utc_offset_min = 0;   // local time − UTC, minutes, within ±18 h (−420 for UTC−7)
};

// Parses an ISO 8601 date and time with a UTC offset (RFC 3339 profile):
// YYYY-MM-DDThh:mm[:ss[.fff…]] followed by Z, ±hh:mm, ±hhmm or ±hh. The separator may also be
// 't' or a space, the decimal mark a comma. The offset is required: a time without one names no
// instant. Throws daylit::Error, quoting the text and saying what is wrong, on anything else,
// including dates that do not exist and ISO 8601 dates before the Gregorian calendar (1582-10-15).
CivilTime parse_iso8601_time(std::string_view text);

// Throws daylit::Error unless t is a valid date and time (the ranges above; years −2000 to 6000,
// the validity of the algorithm).
void check_civil_time(const CivilTime& t);

// Julian Day of the instant t (eq. 4, the time zone subtracted as the report says), UT = UTC:
// add ΔUT1/86400 for UT1. Table A4.1's examples hold to its digits. The result is a double near
// 2.45e6, whose spacing is 40 µs; solar_position() keeps days from J2000.0 to full precision.
double julian_day(const CivilTime& t);

// ΔT = TT − UT1 in seconds from Espenak and Meeus's polynomials (NASA, "Five Millennium Canon of
// Solar Eclipses", NASA/TP-2006-214141; fits to Morrison and Stephenson 2004 and to observed
// values up to 2005), at decimal year y (y = year + (month − 0.5)/12 in their text). Accuracy:
// that of ΔT itself before the telescope (minutes to hours in antiquity), about a second from
// 1800 to 2005; from 2005 on the polynomial is a prediction that by 2024 ran 5 s above the
// observed ΔT (69.2 s). An error of δ seconds in ΔT moves the sun
// along the ecliptic by 1.1e-5° × δ, so 5 s costs 6e-5°, inside the algorithm's ±0.0003°.
// Beyond −1999 and 3000 it continues with their long-term parabola −20 + 32 u², u = (y − 1820)/100.
double delta_t_espenak_meeus(double decimal_year) noexcept;

// What the algorithm needs: when, where, the atmosphere.
struct SolarPositionInput {
  CivilTime time;
  double delta_ut1_s = 0;             // UT1 − UTC, seconds, |·| ≤ 1 (IERS Bulletin A). Ignoring it
                                      // moves the hour angle by up to 0.004° (15″ per second).
  std::optional<double> delta_t_s;    // TT − UT1, seconds, |·| ≤ 1e5; default Espenak–Meeus
  double latitude_deg = 0;            // geodetic, −90 to 90, north positive
  double longitude_deg = 0;           // −180 to 180, east of Greenwich positive
  double elevation_m = 0;             // above the ellipsoid (report: "observer elevation"), > −6378140
  double pressure_hpa = 1013.25;      // annual mean local pressure, 0 to 5000 hPa (= mbar)
  double temperature_c = 10;          // annual mean local temperature, −273 < T ≤ 6000 °C
  double refraction_at_sunrise_deg = 0.5667;  // 0 to 2°: refraction is applied while the sun's
                                              // upper limb (0.26667° radius) is above the horizon
};

// Every intermediate value of the report's procedure (Table A5.1 lists them for its example).
struct SpaSteps {
  double jd = 0;                       // Julian Day, UT1 (eq. 4)
  double jde = 0;                      // Julian Ephemeris Day (eq. 5)
  double jc = 0, jce = 0, jme = 0;     // Julian century, ephemeris century, millennium (eqs. 6–8)
  double delta_t_s = 0;                // the ΔT used
  std::array<double, 6> l_terms{};     // L0…L5 (eq. 10), units of 1e-8 rad
  std::array<double, 2> b_terms{};     // B0, B1
  std::array<double, 5> r_terms{};     // R0…R4, units of 1e-8 AU
  double l_deg = 0;                    // Earth heliocentric longitude L, [0, 360) (eqs. 11–12)
  double b_deg = 0;                    // Earth heliocentric latitude B
  double r_au = 0;                     // Earth radius vector R, AU: the sun's distance
  double theta_deg = 0;                // geocentric longitude Θ (eq. 13)
  double beta_deg = 0;                 // geocentric latitude β (eq. 14)
  std::array<double, 5> x_deg{};       // X0…X4, arguments of the nutation (eqs. 15–19), unreduced
  double delta_psi_deg = 0;            // nutation in longitude Δψ (eq. 22)
  double delta_epsilon_deg = 0;        // nutation in obliquity Δε (eq. 23)
  double epsilon0_arcsec = 0;          // mean obliquity ε0 (eq. 24)
  double epsilon_deg = 0;              // true obliquity ε (eq. 25)
  double delta_tau_deg = 0;            // aberration Δτ (eq. 26)
  double lambda_deg = 0;               // apparent sun longitude λ (eq. 27)
  double nu0_deg = 0;                  // mean sidereal time at Greenwich ν0, [0, 360) (eq. 28)
  double nu_deg = 0;                   // apparent sidereal time at Greenwich ν (eq. 29)
  double alpha_deg = 0;                // geocentric right ascension α, [0, 360) (eq. 30)
  double delta_deg = 0;                // geocentric declination δ (eq. 31)
  double h_deg = 0;                    // observer local hour angle H, [0, 360), westward (eq. 32)
  double xi_deg = 0;                   // equatorial horizontal parallax ξ (eq. 33)
  double delta_alpha_deg = 0;          // parallax in right ascension Δα (eq. 37)
  double alpha_prime_deg = 0;          // topocentric right ascension α′ (eq. 38)
  double delta_prime_deg = 0;          // topocentric declination δ′ (eq. 39)
  double h_prime_deg = 0;              // topocentric local hour angle H′ (eq. 40)
  double e0_deg = 0;                   // topocentric elevation without refraction (eq. 41)
  double delta_e_deg = 0;              // atmospheric refraction correction Δe (eq. 42)
  double e_deg = 0;                    // topocentric elevation e (eq. 43)
  double zenith_deg = 0;               // topocentric zenith angle θ (eq. 44)
  double gamma_deg = 0;                // astronomers' azimuth Γ, westward from south (eq. 45)
  double azimuth_deg = 0;              // azimuth Φ, eastward (clockwise) from north (eq. 46)
  double m_deg = 0;                    // sun's mean longitude M, [0, 360) (eq. A2)
  double equation_of_time_min = 0;     // E, minutes, within ±20 (eq. A1)
};

struct SolarPosition {
  double zenith_deg = 0;               // topocentric, refraction included, 0 to 180
  double azimuth_deg = 0;              // topocentric, clockwise from true north, [0, 360)
  double elevation_deg = 0;            // 90 − zenith
  double declination_deg = 0;          // topocentric δ′
  double hour_angle_deg = 0;           // topocentric H′, [0, 360), westward from the meridian
  double distance_au = 0;              // Earth–sun distance R
  double equation_of_time_min = 0;     // apparent − mean solar time
  SpaSteps steps;
};

// The report's procedure, §3.1–3.15 and A.1 (the surface incidence of §3.16 is left out). Throws
// daylit::Error on input outside the ranges above. Cost: about 240 sines and cosines (5–20 µs).
SolarPosition solar_position(const SolarPositionInput& input);

}  // namespace daylit
