// Triangle meshes: the surfaces of particles and containers (STL, OBJ, OpenFOAM's geometry).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "packbed/vec3.hpp"

namespace packbed {

/// A triangle mesh: triangles index `vertices` counter-clockwise seen from outside (the
/// right-hand normal points out of the body).
struct TriangleMesh {
    std::vector<Vec3> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;

    /// Append another mesh (its indices shifted).
    void append(const TriangleMesh& other);
    /// \return the enclosed volume by the divergence theorem (closed, outward mesh: > 0).
    double volume() const;
};

/// A named closed part of the surface (an STL solid, an OBJ group).
struct Solid {
    std::string name;
    TriangleMesh mesh;
};

} // namespace packbed
