#pragma once
// The sky in Reinhart's patches (Reinhart and Walkenhorst 2001; MF = 1 is Tregenza's 145), as
// patch-based tools (Radiance's gendaymtx and rfluxmtx, DAYSIM, Honeybee) discretise it: each
// patch uniformly at the luminance of its centre, normalised so that the patches' sum gives the
// hour's diffuse horizontal illuminance. Each patch is integrated *exactly* over the visible
// regions (its azimuth wedge cut from the region by two great circles, its altitude band as the
// difference of two caps about the zenith, cap_clip.hpp), so what this mode changes against the
// exact sky is the discretisation alone, and against a patch-based tool its noise alone.

#include <vector>

#include "geometry/scene.hpp"
#include "geometry/spherical_region.hpp"
#include "sky/perez_sky.hpp"
#include "sky/site.hpp"

namespace daylit {

struct SkyPatch {
  double altitude0_deg = 0, altitude1_deg = 0;  // the band (the polar cap: altitude1 = 90)
  double azimuth0_deg = 0, azimuth1_deg = 0;    // clockwise from true north (the polar cap: 0, 360)
  Vec3 centre;                                  // model frame, unit (the polar cap: the zenith)
  Vec3 from, to;                                // the wedge's planes through z: keep from·u ≥ 0, to·u ≥ 0
  double solid_angle = 0;                       // sr, exact
};

// The patches of subdivision MF (1..6) in the model frame of `site`: rows of 90°/(7 MF + 0.5) in
// altitude with {30, 30, 24, 24, 18, 12, 6}·MF patches (each of Tregenza's rows split MF times),
// the first patch of every row centred on true north (as reinhart_patch_centre), and the polar
// cap of half a row: 144 MF² + 1 patches.
std::vector<SkyPatch> reinhart_patches(int mf, const Site& site);

// Adds ∫_{R ∩ P} (n·u) T dσ for every patch P into `coefficients` (one per patch) for the region
// R seen through `transmitting`: exact for a constant T; glass's T(μ) is taken at each part's
// centroid direction (∫_part u dσ, by the same caps), and `spread` (the largest relative
// half-range of T over the part's azimuth wedge of R, which holds the part) bounds what that costs.
// `sign` −1 subtracts (a count taken back: PaneView).
void add_patch_coefficients(const std::vector<SkyPatch>& patches, const SphericalRegion& region, const Vec3& n,
                            const Aperture& transmitting, std::vector<double>& coefficients, double& spread,
                            double sign = 1);

// One hour's patch luminances (lux per sr, so that E = Σ_P coefficient_P · luminance_P): the
// sky's relative luminance at each centre, scaled so that Σ_P L_P ω_P sin(altitude_P) is the hour's
// diffuse horizontal illuminance, as gendaymtx normalises (the sum over the centres, not the
// exact integral: that is the discretisation this mode reproduces).
std::vector<double> patch_luminances(const std::vector<SkyPatch>& patches, const PerezSky& sky, double diffuse_horizontal_lux);

}  // namespace daylit
