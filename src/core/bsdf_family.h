// The families of BSDFs a material resolves into (core/bsdf.h's makeBsdf); each
// transport model names its own (core/shading_model.h).
#pragma once

namespace penumbra {

// Phong: the report's k_d, k_s and mirror terms with p_r / p_t photon roulette.
// Radiometric: Lambert, normalised Phong, glass and GGX in radiometric units.
enum class BsdfFamily { Phong, Radiometric };

// Radiometric BSDFs return at most what arrives, so a loader bounds a material's
// reflectances and glass tints by 1 for them; Phong terms are free.
inline constexpr bool boundsAlbedo(BsdfFamily family) { return family == BsdfFamily::Radiometric; }

}  // namespace penumbra
