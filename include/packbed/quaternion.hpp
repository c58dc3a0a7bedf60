// A rotation as a unit quaternion: the orientation of a particle whose shape has one.
#pragma once

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

} // namespace packbed
