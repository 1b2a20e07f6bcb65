// Fuzz target: the site description reader (sky/site.hpp) on arbitrary bytes. Any input must end
// in a Site or in a daylit::Error naming the file; a site that is accepted must place points
// finitely.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "geometry/error.hpp"
#include "sky/site.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const daylit::Site site = daylit::parse_site_json(text, "fuzz.json");
    const daylit::Vec3 x = site.model_from_wgs84(site.origin().latitude_deg, site.origin().longitude_deg, 0);
    if (!daylit::is_finite(x) || !daylit::is_finite(site.true_north_in_model())) {
      std::fprintf(stderr, "a site that was accepted places its origin at a non-finite point\n");
      std::abort();
    }
  } catch (const daylit::Error& e) {
    if (std::string(e.what()).rfind("fuzz.json", 0) != 0) {
      std::fprintf(stderr, "error message lacks the file: %s\n", e.what());
      std::abort();
    }
  }
  return 0;
}
