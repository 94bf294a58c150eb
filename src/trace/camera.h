// The camera: maps a film position to a primary ray, through a pinhole or a thin
// lens, or, for an orthographic camera, along the view direction from a point on the
// film plane.
#pragma once
#include "core/camera_frame.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/scene.h"
#include "core/thin_lens.h"
#include "geometry/ray.h"

namespace penumbra {

class CameraRays {
 public:
  explicit CameraRays(const Camera& c) : origin_(c.position), width_(c.width), height_(c.height) {
    const CameraFrame frame = cameraFrame(c);
    forward_ = frame.forward;
    right_ = frame.right;
    up_ = frame.up;
    tanHalf_ = std::tan(glm::radians(c.fovY) * 0.5f);
    aspect_ = static_cast<float>(c.width) / static_cast<float>(c.height);
    halfHeight_ = 0.5f * c.orthoHeight;
    lensRadius_ = lensRadius(c);
    focus_ = focusDistance(c);
  }
  // (fx, fy) in pixels from the top-left corner of the film.
  Ray generate(float fx, float fy) const {
    float sx = (2.0f * fx / width_ - 1.0f) * aspect_ * tanHalf_;
    float sy = (1.0f - 2.0f * fy / height_) * tanHalf_;
    Ray r;
    if (halfHeight_ > 0.0f) {  // orthographic: parallel rays from the film plane
      r.origin = origin_ + (sx / tanHalf_ * halfHeight_) * right_ + (sy / tanHalf_ * halfHeight_) * up_;
      r.dir = forward_;
      return r;
    }
    r.origin = origin_;
    r.dir = glm::normalize(forward_ + sx * right_ + sy * up_);
    return r;
  }
  // The ray of camera sample `key` (its (seed, pixel, sample) stream): through the
  // thin lens, when there is one, at a point of the aperture drawn from the key; else
  // exactly generate(fx, fy).
  Ray generate(float fx, float fy, uint64_t key) const {
    Ray r = generate(fx, fy);
    if (lensRadius_ > 0.0f) throughLens(r, key);
    return r;
  }
  // Angle one pixel subtends at the centre: the texture-footprint growth rate (0
  // for parallel rays, whose footprint does not grow; textures are then point-sampled).
  float pixelSpread() const { return halfHeight_ > 0.0f ? 0.0f : 2.0f * tanHalf_ / height_; }

 private:
  // The pinhole ray's point on the focus plane (its direction's forward part is 1 before
  // normalising, so the plane is focus_ away along forward_) is sharp: every lens point
  // aims at it. The aperture point is uniform over the disk (concentric map) from two
  // numbers of the sample's own stream, apart from the ones its shading draws.
  void throughLens(Ray& r, uint64_t key) const {
    const uint64_t bits = hashKey(key, kLensStream);
    const float u1 = static_cast<float>(bits >> 40) * 0x1p-24f, u2 = static_cast<float>((bits >> 8) & 0xFFFFFFu) * 0x1p-24f;
    const Vec2 d = lensRadius_ * concentricDisk(u1, u2);
    const Vec3 focal = r.origin + r.dir * (focus_ / glm::dot(r.dir, forward_));
    r.origin += d.x * right_ + d.y * up_;
    r.dir = glm::normalize(focal - r.origin);
  }
  static constexpr uint64_t kLensStream = 0x6c656e73ull;  // "lens"

  Vec3 origin_, forward_, right_, up_;
  float tanHalf_ = 1.0f, aspect_ = 1.0f, halfHeight_ = 0.0f, lensRadius_ = 0.0f, focus_ = 1.0f;
  int width_, height_;
};

}  // namespace penumbra
