// The camera: maps a film position to a primary ray, through a pinhole or, for an
// orthographic camera, along the view direction from a point on the film plane.
#pragma once
#include "core/camera_frame.h"
#include "core/scene.h"
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
  // Angle one pixel subtends at the centre: the texture-footprint growth rate (0
  // for parallel rays, whose footprint does not grow; textures are then point-sampled).
  float pixelSpread() const { return halfHeight_ > 0.0f ? 0.0f : 2.0f * tanHalf_ / height_; }

 private:
  Vec3 origin_, forward_, right_, up_;
  float tanHalf_ = 1.0f, aspect_ = 1.0f, halfHeight_ = 0.0f;
  int width_, height_;
};

}  // namespace penumbra
