// read_bed_summary on a stream (a bed's summary.json: container radius, diameter and
// porosity): what is
// present is in range, or InvalidInput.
#include "fuzz_support.hpp"
#include "packbed/limits.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using packbed::fuzz::finding;
    std::istringstream input(packbed::fuzz::text_of(data, size));
    try {
        const packbed::BedSummary s = packbed::read_bed_summary(input, "summary.json");
        if (s.container_radius &&
            !(*s.container_radius > 0 && *s.container_radius <= packbed::limits::max_length))
            finding("read_bed_summary returned container radius " +
                    std::to_string(*s.container_radius));
        if (s.diameter && !(*s.diameter > 0 && *s.diameter <= packbed::limits::max_diameter))
            finding("read_bed_summary returned diameter " + std::to_string(*s.diameter));
        if (s.porosity && !(*s.porosity > 0 && *s.porosity < 1))
            finding("read_bed_summary returned porosity " + std::to_string(*s.porosity));
        if (s.porosity.has_value() == s.porosity_source.empty())
            finding("read_bed_summary returned a porosity without its source, or a source "
                    "without a porosity");
    } catch (const packbed::InvalidInput&) {
    } catch (...) {
        packbed::fuzz::unexpected_exception();
    }
    return 0;
}
