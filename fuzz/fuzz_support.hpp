// What the fuzz targets share: the rule that a reader either returns a valid result or throws
// one of the exception types it documents. Anything else is a finding: the target prints it
// and aborts, and libFuzzer saves the input (crash-<hash>) and prints the stack.
#pragma once

#include <cinttypes>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <typeinfo>
#include <vector>

#include <cxxabi.h>

#include "packbed/error.hpp"
#include "packbed/read.hpp"

namespace packbed::fuzz {

/// The input bytes as a string (readers take streams).
inline std::string text_of(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

/// Report a finding and abort (libFuzzer then saves the input and prints the stack).
[[noreturn]] inline void finding(std::string_view what) {
    std::fprintf(stderr, "\n==packbed-fuzz== FINDING: %.*s\n", static_cast<int>(what.size()),
                 what.data());
    std::fflush(stderr);
    std::abort();
}

/// FNV-1a, 64 bits, continued from `h` (src/generate/checkpoint.cpp).
inline std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = 0xcbf29ce484222325ULL) {
    for (const char c : bytes) {
        h ^= static_cast<unsigned char>(c);
        h *= 0x100000001b3ULL;
    }
    return h;
}

/// A checkpoint's `text` with its third line replaced by `fnv1a64 HEX`, the hash of the second
/// line, a newline and everything after the third line (as src/generate/checkpoint.cpp signs
/// it); nothing when it has fewer than three lines.
inline std::optional<std::string> resigned(std::string_view text) {
    const auto first = text.find('\n');
    if (first == std::string_view::npos)
        return std::nullopt;
    const auto second = text.find('\n', first + 1);
    if (second == std::string_view::npos)
        return std::nullopt;
    const auto third = text.find('\n', second + 1);
    if (third == std::string_view::npos)
        return std::nullopt;
    const std::string_view header = text.substr(first + 1, second - first - 1);
    const std::string_view data = text.substr(third + 1);
    char hash[40];
    std::snprintf(hash, sizeof hash, "fnv1a64 %016" PRIx64 "\n",
                  fnv1a(data, fnv1a("\n", fnv1a(header))));
    return std::string(text.substr(0, second + 1)) + hash + std::string(data);
}

/// A fuzz input read as a checkpoint twice, as it is and re-signed (resigned): `read` is
/// given a stream of each; an InvalidInput is the reader's refusal, any other exception a
/// finding.
template <class F>
void read_as_is_and_resigned(const std::uint8_t* data, std::size_t size, F&& read);

/// The demangled name of a type.
inline std::string type_name(const std::type_info& type) {
    int status = 0;
    std::unique_ptr<char, void (*)(void*)> name(
        abi::__cxa_demangle(type.name(), nullptr, nullptr, &status), std::free);
    return status == 0 && name ? std::string(name.get()) : std::string(type.name());
}

/// Call from a `catch (...)` after the expected types: names the exception and aborts.
[[noreturn]] inline void unexpected_exception() {
    try {
        throw;
    } catch (const std::exception& e) {
        finding("unexpected exception " + type_name(typeid(e)) + ": " + e.what());
    } catch (...) {
        finding("unexpected exception of a type not derived from std::exception");
    }
}

/// What read_particles promises of what it returns: one line number per sphere, increasing,
/// finite centres, finite radii > 0, at least one sphere.
inline void check_particles(const ParticleFile& file) {
    const Packing& p = file.packing;
    if (p.size() == 0)
        finding("read_particles returned no spheres");
    if (p.radii.size() != p.size() || file.lines.size() != p.size())
        finding("read_particles returned arrays of different lengths");
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec3& c = p.centers[i];
        if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z))
            finding("read_particles returned a centre that is not finite, line " +
                    std::to_string(file.lines[i]));
        if (!std::isfinite(p.radii[i]) || !(p.radii[i] > 0.0))
            finding("read_particles returned a radius that is not finite and > 0, line " +
                    std::to_string(file.lines[i]));
        if (file.lines[i] == 0 || (i > 0 && file.lines[i] <= file.lines[i - 1]))
            finding("read_particles returned line numbers that are not increasing from 1");
    }
}

/// What read_particle_frames promises of each frame: as check_particles, except that a frame
/// may have no spheres; frames numbered 1, 2, ... in order.
inline void check_frames(const std::vector<ParticleFile>& frames) {
    if (frames.empty())
        finding("read_particle_frames returned no frame");
    for (std::size_t k = 0; k < frames.size(); ++k) {
        if (frames[k].frame != k + 1)
            finding("read_particle_frames returned frames not numbered 1, 2, ... in order");
        if (frames[k].packing.size() > 0)
            check_particles(frames[k]);
        else if (!frames[k].lines.empty() || !frames[k].packing.radii.empty())
            finding("read_particle_frames returned an empty frame with lines or radii");
    }
}

/// read_particle_frames on the input: valid frames or InvalidInput, nothing else.
inline void read_frames_or_invalid(const std::uint8_t* data, std::size_t size,
                                   std::string_view name, ParticleFormat format,
                                   const ReadOptions& options = {}) {
    std::istringstream input(text_of(data, size));
    try {
        check_frames(read_particle_frames(input, name, format, options));
    } catch (const InvalidInput&) {
    } catch (...) {
        unexpected_exception();
    }
}

/// Options that exercise the rest of the reader: a radius for files without one, a frame
/// counted from the end (read twice), an axis and a floor, a small limit on decompressed
/// bytes (gzip inputs).
inline ReadOptions other_options() {
    ReadOptions o;
    o.radius = 0.5;
    o.frame = -2;
    o.axis = {1.5, -2.0};
    o.floor = 0.25;
    o.max_bytes = 4096;
    return o;
}

/// read_particles on the input: a valid ParticleFile or InvalidInput, nothing else.
inline void read_particles_or_invalid(const std::uint8_t* data, std::size_t size,
                                      std::string_view name, ParticleFormat format,
                                      const ReadOptions& options = {}) {
    std::istringstream input(text_of(data, size));
    try {
        check_particles(read_particles(input, name, format, options));
    } catch (const InvalidInput&) {
    } catch (...) {
        unexpected_exception();
    }
}

template <class F>
void read_as_is_and_resigned(const std::uint8_t* data, std::size_t size, F&& read) {
    const auto once = [&](const std::string& text) {
        std::istringstream input(text);
        try {
            read(input);
        } catch (const InvalidInput&) {
        } catch (...) {
            unexpected_exception();
        }
    };
    const std::string text = text_of(data, size);
    once(text);
    if (const auto signed_text = resigned(text); signed_text && *signed_text != text)
        once(*signed_text);
}

} // namespace packbed::fuzz
