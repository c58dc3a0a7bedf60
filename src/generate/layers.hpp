// Internal: which particles of a bed in layers take part in one layer's relaxation, shared by
// the sphere beds' fire solver (fire.cpp, relax_with_fire) and the pellet beds
// (pellet_bed.cpp, pellets_in_layers).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace packbed::detail {

/// Layer l's part of a bed in layers before its own slice is added: the held shell first, then
/// the free band (each in a fixed order), and the height between them.
struct LayerPart {
    std::vector<std::uint32_t> ids;
    std::size_t fixed = 0; ///< the first `fixed` of ids are held
    double datum = 0.0;    ///< below it the shell, above it the band
};

/// The band is the last layer relaxed before l (`previous`, the last one below l holding any
/// particle) and the top `band_height` of the layers under it (above the datum, the highest
/// centre under `previous` less band_height); the shell is the particles of those layers
/// within `shell` below the datum. Nothing is held while the layers under `previous` hold no
/// particle (the datum is 0). `members[k]` holds layer k's particles, `z(i)` is particle i's
/// height now.
template <class Z>
LayerPart layer_part(const std::vector<std::vector<std::uint32_t>>& members, std::uint32_t l, Z&& z,
                     double band_height, double shell) {
    std::uint32_t previous = l;
    for (std::uint32_t below = 0; below < l; ++below)
        if (!members[below].empty())
            previous = below;
    bool under = false;
    double under_top = 0.0; // highest centre under the previous layer
    for (std::uint32_t below = 0; below < previous; ++below)
        for (const std::uint32_t i : members[below]) {
            under_top = under ? std::max(under_top, z(i)) : z(i);
            under = true;
        }
    LayerPart part;
    part.datum = under ? under_top - band_height : 0.0;
    std::vector<std::uint32_t> band;
    for (std::uint32_t below = 0; below < l; ++below) // the settled layers
        for (const std::uint32_t i : members[below]) {
            if (below == previous || z(i) > part.datum)
                band.push_back(i);
            else if (z(i) > part.datum - shell)
                part.ids.push_back(i);
        }
    part.fixed = part.ids.size();
    part.ids.insert(part.ids.end(), band.begin(), band.end());
    return part;
}

} // namespace packbed::detail
