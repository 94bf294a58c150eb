// The built-in Utah teapot: Newell's 32 Bezier patches tessellated into a
// smooth-shaded, welded TriangleMesh.
#pragma once
#include "core/scene.h"

namespace penumbra {

// Tessellates each of the 32 bicubic patches on an (N+1)x(N+1) grid of its
// (u, v) parameters, N = subdivisions in [1, 128] (InputError otherwise).
//
// Frame: the data set is z-up; it is rotated -90 degrees about x, so
// (x, y, z)_data -> (x, z, -y), then uniformly scaled by 1/3.15 (the data's
// height, knob top z = 3.15). The teapot stands on y = 0 with the top of the
// knob at y = 1, spout towards +x, handle towards -x; body centred on the y axis.
// Surface bounds (from the patch data, so independent of N up to tessellation):
// x in [-0.952, 1.090], y in [0, 1], z in [-0.635, 0.635] (x max
// approaches 1.0902 as N grows: the spout lip lies between grid points).
//
// Output: positions, unit outward vertex normals (from the Bezier partial
// derivatives; at the knob top and base centre, where a whole patch edge is one
// point, the limit from inside the patch), per-patch uvs (u, v in [0, 1]) and
// counter-clockwise triangles seen from outside. Coincident vertices (found by
// a quantised-position hash) share one averaged normal, so patch edges shade
// seamlessly; normals differing by more than 60 degrees are not averaged (the
// handle's lower end touches a body patch corner). Vertices are merged only when
// their uvs agree too, so each patch keeps its own [0, 1] texture square;
// triangles collapsing to zero area are dropped (N per knob and base patch, so
// 64 N^2 - 8 N triangles for N >= 2). Like the original, the mesh is not
// watertight: the lid floats in the rim; spout and handle pierce the body.
TriangleMesh makeTeapot(int subdivisions);

}  // namespace penumbra
