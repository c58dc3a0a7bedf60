// read_checkpoint on a stream, for the parameters the seed checkpoints were taken with
// (`packbed generate --solver fire -a 3 -n 200 --layer-height 10`, seed 1): a checkpoint that
// a run can resume from, or InvalidInput.
//
// Format 3's hash covers the header line and the data, so nearly every change the fuzzer makes
// would stop at the hash check. Each input is therefore read twice: as it is, and "re-signed"
// (its third line replaced by the right hash of its second line and its data, as
// src/generate/checkpoint.cpp computes it), which takes the fuzzer's changes to the range checks of
// every field behind the hash. If the hash's definition changes, change fuzz::resigned() with
// it.
#include <optional>

#include "fuzz_support.hpp"
#include "packbed/checkpoint.hpp"

namespace {

packbed::SoftSphereParameters seed_parameters() {
    packbed::SoftSphereParameters p;
    p.container = packbed::Container::tube(3);
    p.particles = 200;
    p.solver = packbed::Solver::fire;
    p.layer_height = 10;
    return p;
}

const packbed::SoftSphereParameters parameters = seed_parameters();

/// What a run resumes from: every sphere, finite, with a radius > 0, a layer count within the
/// run's, the three stage records, finite values.
void check(const packbed::LayerCheckpoint& c) {
    using packbed::fuzz::finding;
    const packbed::Packing& p = c.packing;
    if (p.size() != parameters.particles || p.radii.size() != p.size())
        finding("read_checkpoint returned " + std::to_string(p.size()) + " spheres for a run of " +
                std::to_string(parameters.particles));
    for (std::size_t i = 0; i < p.size(); ++i)
        if (!std::isfinite(p.centers[i].x) || !std::isfinite(p.centers[i].y) ||
            !std::isfinite(p.centers[i].z) || !std::isfinite(p.radii[i]) || !(p.radii[i] > 0))
            finding("read_checkpoint returned sphere " + std::to_string(i) +
                    " not finite or with a radius <= 0");
    const std::uint32_t layers = packbed::fire_layers(parameters);
    if (c.layers_done < 1 || c.layers_done > layers)
        finding("read_checkpoint returned layers_done = " + std::to_string(c.layers_done) +
                " for a run of " + std::to_string(layers) + " layers");
    if (!std::isfinite(c.top))
        finding("read_checkpoint returned a top that is not finite");
    if (c.stages.size() != 3)
        finding("read_checkpoint returned " + std::to_string(c.stages.size()) +
                " stage records, not 3");
    for (const auto& s : c.stages) {
        if (!std::isfinite(s.cg) || !std::isfinite(s.max_overlap_pair) ||
            !std::isfinite(s.max_overlap_wall) || !std::isfinite(s.mass_centre_z))
            finding("read_checkpoint returned a stage record that is not finite");
        if (s.mass_centre_window.size() > parameters.mc_window)
            finding("read_checkpoint returned a mass-centre window longer than mc_window");
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    packbed::fuzz::read_as_is_and_resigned(data, size, [](std::istream& input) {
        check(packbed::read_checkpoint(input, "fuzz.checkpoint", parameters));
    });
    return 0;
}
