#pragma once
// The notes' transformations as homogeneous matrices (column vectors, P' = M P).
//
// 2D transforms are 3x3 (points are [x, y, 1]), 3D transforms 4x4 (points are [x, y, z, 1]). Each function's comment
// gives its matrix in the notes' row-major notation [row; row; ...]. Angles are radians, counterclockwise when looking
// down the axis toward the origin ("start on the positive axis and rotate toward the negative one").
#include "tessera/math/types.hpp"

namespace tessera {

// ---- 2D (Mat3) -----------------------------------------------------------------------------------------------------

/// [1 0 dx; 0 1 dy; 0 0 1]
Mat3 translate2d(double dx, double dy);
/// [sx 0 0; 0 sy 0; 0 0 1]
Mat3 scale2d(double sx, double sy);
/// [cos -sin 0; sin cos 0; 0 0 1]: counterclockwise about the origin.
Mat3 rotate2d(double theta);
/// x' = x + a y, y' = y + b x: [1 a 0; b 1 0; 0 0 1] (the notes' shear is b = 0).
Mat3 shear2d(double a, double b = 0);
/// x' = -x (reflection in the y axis): [-1 0 0; 0 1 0; 0 0 1]
Mat3 reflect2d_y_axis();
/// y' = -y (reflection in the x axis): [1 0 0; 0 -1 0; 0 0 1]
Mat3 reflect2d_x_axis();
/// Rotation about the point (cx, cy): T2 R T1 of the notes (translate to the origin, rotate, translate back).
Mat3 rotate2d_about(double theta, double cx, double cy);

// ---- 3D (Mat4) -----------------------------------------------------------------------------------------------------

/// [1 0 0 dx; 0 1 0 dy; 0 0 1 dz; 0 0 0 1]
Mat4 translate(double dx, double dy, double dz);
/// [sx 0 0 0; 0 sy 0 0; 0 0 sz 0; 0 0 0 1]
Mat4 scale(double sx, double sy, double sz);
/// Rx = [1 0 0 0; 0 cos -sin 0; 0 sin cos 0; 0 0 0 1]
Mat4 rotate_x(double theta);
/// Ry = [cos 0 sin 0; 0 1 0 0; -sin 0 cos 0; 0 0 0 1]
Mat4 rotate_y(double theta);
/// Rz = [cos -sin 0 0; sin cos 0 0; 0 0 1 0; 0 0 0 1]
Mat4 rotate_z(double theta);
/// Rotation by theta about the axis (ax, ay, az) through the origin, built the notes' way: the orthonormal frame
/// A = axis/|axis|, B = A x N / |A x N| (N = (1,0,0) if ax = 0, else (0,1,0)), C = A x B gives R1 = [A; B; C]
/// (rows), and R = R1^T Rx(theta) R1. Equals glRotate. Throws InvalidInput for a zero axis.
Mat4 rotate(double theta, const Vec3& axis);
/// The notes' R1: the rotation whose rows are the frame A, B, C (it maps the axis A onto +x).
Mat4 axis_frame(const Vec3& axis);
/// Shear of x by y and z, y by x and z, z by x and y: [1 xy xz 0; yx 1 yz 0; zx zy 1 0; 0 0 0 1].
Mat4 shear(double xy, double xz, double yx, double yz, double zx, double zy);
/// Reflection through the plane through the origin with the given normal: I - 2 n n^T.
Mat4 reflect(const Vec3& plane_normal);

// ---- Viewing -------------------------------------------------------------------------------------------------------

/// The view matrix of camera(eye, center, up), the notes' M_view = R T: T = translate(-eye), w = -g/|g| for the gaze
/// g = center - eye, u = up x w / |up x w|, v = w x u, R = [u; v; w] (rows). Equals gluLookAt. Throws InvalidInput
/// when eye == center or up is parallel to the gaze.
Mat4 look_at(const Vec3& eye, const Vec3& center, const Vec3& up);

/// Orthographic projection of the box x in [l, r], y in [b, t], z in [-n, -f] (n, f are distances in front of the
/// camera, as glOrtho) onto the clip cube [-1, 1]^3:
/// [2/(r-l) 0 0 -(r+l)/(r-l); 0 2/(t-b) 0 -(t+b)/(t-b); 0 0 -2/(f-n) -(f+n)/(f-n); 0 0 0 1].
Mat4 ortho(double l, double r, double b, double t, double n, double f);

/// Perspective projection with vertical field of view fovy (radians), aspect = width/height and near/far distances
/// n, f > 0, as gluPerspective: with k = tan(fovy/2), [1/(aspect k) 0 0 0; 0 1/k 0 0;
/// 0 0 -(f+n)/(f-n) -2fn/(f-n); 0 0 -1 0]. After the divide, x' = x/|z| / (aspect k), the notes' y' = y/|z| mapped to
/// [-k, k]. Throws InvalidInput for fovy outside (0, pi), aspect <= 0, or not 0 < n < f.
Mat4 perspective(double fovy, double aspect, double n, double f);

/// perspective with the far plane at infinity (f -> inf): [1/(aspect k) 0 0 0; 0 1/k 0 0; 0 0 -1 -2n; 0 0 -1 0]. A
/// point at infinity in front of the camera, (d, 0) with d.z < 0, lands on the far plane (z = w) instead of beyond
/// it, as z-fail shadow volumes need (Everitt and Kilgard 2002). Throws as perspective for fovy, aspect or n <= 0.
Mat4 infinite_perspective(double fovy, double aspect, double n);

/// The normal matrix: inverse transpose of the upper-left 3x3 of a model-view matrix.
Mat3 normal_matrix(const Mat4& model_view);

/// Applies a homogeneous 3D transform to a point (w = 1) and divides by w.
Vec3 transform_point(const Mat4& m, const Vec3& p);
/// Applies the linear part of a 3D transform to a direction (w = 0).
Vec3 transform_vector(const Mat4& m, const Vec3& v);
/// Applies a 2D homogeneous transform to a point.
Vec2 transform_point(const Mat3& m, const Vec2& p);

}  // namespace tessera
