// How far the exact cylinders of a multisphere bed overlap: LIGGGHTS' clumps of spheres
// (bench/peers/liggghts_pellets.sh) settle on their spheres, and the cylinders they stand for
// are measured here by packbed's exact depths (CylinderShape::pair_overlap, wall_overlap).
// Reads the bodies' dump (`write_dump all local`: the centre of mass, the principal moments,
// the principal axes), takes each pellet's axis as the principal axis whose moment differs most
// from the other two, and prints the deepest and the mean overlap of touching pairs, and the
// deepest reach into the tube's wall or the floor, in units of D.
// Usage: clump_overlaps BODIES_DUMP D L RT   (lengths in the dump's unit; RT the tube's radius)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "packbed/container.hpp"
#include "packbed/cylinder_shape.hpp"
#include "packbed/quaternion.hpp"

using namespace packbed;

int main(int argc, char** argv) {
    if (argc != 5) {
        std::fprintf(stderr, "usage: clump_overlaps BODIES_DUMP D L RT\n");
        return 2;
    }
    std::ifstream in(argv[1]);
    const double d = std::atof(argv[2]), l = std::atof(argv[3]), rt = std::atof(argv[4]);
    if (!in || !(d > 0.0) || !(l > 0.0) || !(rt > 0.0)) {
        std::fprintf(stderr, "clump_overlaps: cannot read %s, or D, L, RT not all > 0\n", argv[1]);
        return 2;
    }
    std::string line;
    while (std::getline(in, line) && line.rfind("ITEM: ENTRIES", 0) != 0) {
    }
    const double size = 0.5 * std::cbrt(1.5 * d * d * l); // d_v / 2
    std::vector<Placement> pellets;
    while (std::getline(in, line)) {
        std::istringstream row(line);
        double v[15];
        int k = 0;
        while (k < 15 && (row >> v[k]))
            ++k;
        if (k < 15)
            continue;
        int axis = 0;
        double apart = -1.0;
        for (int i = 0; i < 3; ++i) {
            double least = 1e300;
            for (int j = 0; j < 3; ++j)
                if (j != i)
                    least = std::min(least, std::abs(v[3 + i] - v[3 + j]));
            if (least > apart) {
                apart = least;
                axis = i;
            }
        }
        Vec3 a{v[6 + 3 * axis], v[7 + 3 * axis], v[8 + 3 * axis]};
        a = a * (1.0 / norm(a));
        // The turn that takes the body z axis to a (about their cross product).
        const Vec3 c = cross(Vec3{0.0, 0.0, 1.0}, a);
        const double s = norm(c);
        const Vec3 turn = s > 1e-15 ? c * (std::atan2(s, a.z) / s) : Vec3{};
        pellets.push_back({{v[0], v[1], v[2]}, rotation_by(turn), size});
    }
    const CylinderShape cylinder = CylinderShape::of_aspect(l / d);
    const Container tube = Container::tube(2.0 * rt);
    double deepest = 0.0, wall = 0.0, sum = 0.0;
    int touching = 0;
    for (std::size_t i = 0; i < pellets.size(); ++i) {
        wall = std::max({wall, cylinder.wall_overlap(tube, pellets[i]),
                         -cylinder.support(pellets[i], {0.0, 0.0, -1.0}).z});
        for (std::size_t j = i + 1; j < pellets.size(); ++j) {
            const Vec3 ab = pellets[j].position - pellets[i].position;
            if (norm(ab) > 2.0 * cylinder.bounding_radius(size))
                continue;
            const double depth = cylinder.pair_overlap(pellets[i], cylinder, pellets[j], ab).depth;
            if (depth > 0.0) {
                ++touching;
                sum += depth;
                deepest = std::max(deepest, depth);
            }
        }
    }
    std::printf("pellets %zu overlapping_pairs %d deepest_pair %.4g mean_pair %.4g wall %.4g "
                "(units of D)\n",
                pellets.size(), touching, deepest / d, touching ? sum / touching / d : 0.0,
                wall / d);
    return 0;
}
