#include "packbed/mesh.hpp"

namespace packbed {

void TriangleMesh::append(const TriangleMesh& other) {
    const auto shift = static_cast<std::uint32_t>(vertices.size());
    vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
    for (const auto& t : other.triangles)
        triangles.push_back({t[0] + shift, t[1] + shift, t[2] + shift});
}

double TriangleMesh::volume() const {
    double six_v = 0.0;
    for (const auto& t : triangles)
        six_v += dot(vertices[t[0]], cross(vertices[t[1]], vertices[t[2]]));
    return six_v / 6.0;
}

} // namespace packbed
