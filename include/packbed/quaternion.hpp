// A rotation as a unit quaternion: the orientation of a particle whose shape has one.
#pragma once

#include <cmath>
#include <numbers>

#include "packbed/vec3.hpp"

namespace packbed {

/// The unit quaternion q = w + x i + y j + z k of a rotation: a particle's body frame turned
/// into the bed's (the pellet's axis is its body z axis, `particles.csv`'s qw,qx,qy,qz when
/// pellets come, docs/design.md "Particles"). The default is the identity. Plain value type.
struct Quaternion {
    double w = 1.0;
    double x = 0.0;
    double y = 0.0;
    double z = 0.0;
    friend constexpr bool operator==(const Quaternion&, const Quaternion&) = default;
};

/// v turned by the unit quaternion q: v + 2 w (u x v) + 2 u x (u x v) with u = (x, y, z)
/// (the sandwich product q v q*, expanded; Kuipers, "Quaternions and Rotation Sequences",
/// 1999, sec. 5.14).
constexpr Vec3 rotate(const Quaternion& q, const Vec3& v) {
    const Vec3 u{q.x, q.y, q.z};
    const Vec3 t = 2.0 * cross(u, v);
    return v + q.w * t + cross(u, t);
}

/// The inverse rotation of a unit quaternion (its conjugate).
constexpr Quaternion conjugate(const Quaternion& q) {
    return {q.w, -q.x, -q.y, -q.z};
}

/// The product a b: the rotation b, then a (Hamilton's product).
constexpr Quaternion operator*(const Quaternion& a, const Quaternion& b) {
    return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
            a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
            a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
            a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

/// q scaled to unit length (the identity for a zero quaternion).
inline Quaternion normalized(const Quaternion& q) {
    const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    return n > 0.0 ? Quaternion{q.w / n, q.x / n, q.y / n, q.z / n} : Quaternion{};
}

/// The rotation by |v| radians about v / |v| (the exponential map; the identity for v = 0).
inline Quaternion rotation_by(const Vec3& v) {
    const double angle = norm(v);
    if (angle == 0.0)
        return {};
    const double s = std::sin(0.5 * angle) / angle;
    return {std::cos(0.5 * angle), v.x * s, v.y * s, v.z * s};
}

/// The rotation that three independent uniform numbers u1, u2, u3 in [0, 1) make uniformly
/// random over all rotations (Shoemake, "Uniform random rotations", Graphics Gems III, 1992):
/// (sqrt(u1) cos 2 pi u3, sqrt(1 - u1) sin 2 pi u2, sqrt(1 - u1) cos 2 pi u2, sqrt(u1) sin 2 pi
/// u3).
inline Quaternion uniform_rotation(double u1, double u2, double u3) {
    const double t2 = 2.0 * std::numbers::pi * u2, t3 = 2.0 * std::numbers::pi * u3;
    const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
    return {b * std::cos(t3), a * std::sin(t2), a * std::cos(t2), b * std::sin(t3)};
}

} // namespace packbed
