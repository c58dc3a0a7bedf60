#include "packbed/io.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include <fmt/format.h>

#include "packbed/error.hpp"

namespace packbed {

std::string particles_csv(const Packing& packing) {
    fmt::memory_buffer out;
    fmt::format_to(std::back_inserter(out), "x,y,z,r\n");
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const Vec3& c = packing.centers[i];
        // fmt's "{}" for double is the shortest representation that round-trips.
        fmt::format_to(std::back_inserter(out), "{},{},{},{}\n", c.x, c.y, c.z, packing.radii[i]);
    }
    return fmt::to_string(out);
}

AxisBox bounding_box(const Packing& packing) {
    if (packing.size() == 0)
        return {{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}};
    const double inf = std::numeric_limits<double>::infinity();
    AxisBox box{{inf, inf, inf}, {-inf, -inf, -inf}};
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const Vec3 c = packing.centers[i];
        const double r = packing.radii[i];
        box.lo = {std::min(box.lo.x, c.x - r), std::min(box.lo.y, c.y - r),
                  std::min(box.lo.z, c.z - r)};
        box.hi = {std::max(box.hi.x, c.x + r), std::max(box.hi.y, c.y + r),
                  std::max(box.hi.z, c.z + r)};
    }
    return box;
}

std::string lammps_data(const Packing& packing, double density, const AxisBox& box,
                        std::string_view comment) {
    if (!(std::isfinite(density) && density > 0.0))
        throw InvalidInput(
            fmt::format("density = {} is not allowed; allowed: a number > 0", density));
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const Vec3 c = packing.centers[i];
        if (!(c.x >= box.lo.x && c.x <= box.hi.x && c.y >= box.lo.y && c.y <= box.hi.y &&
              c.z >= box.lo.z && c.z <= box.hi.z))
            throw InvalidInput(fmt::format(
                "sphere {} at ({}, {}, {}) lies outside the box [{}, {}] x [{}, {}] x [{}, {}]; "
                "allowed: a box holding every centre",
                i + 1, c.x, c.y, c.z, box.lo.x, box.hi.x, box.lo.y, box.hi.y, box.lo.z, box.hi.z));
    }
    fmt::memory_buffer out;
    fmt::format_to(std::back_inserter(out), "{}\n\n{} atoms\n1 atom types\n\n", comment,
                   packing.size());
    fmt::format_to(std::back_inserter(out), "{} {} xlo xhi\n{} {} ylo yhi\n{} {} zlo zhi\n\n",
                   box.lo.x, box.hi.x, box.lo.y, box.hi.y, box.lo.z, box.hi.z);
    fmt::format_to(std::back_inserter(out), "Atoms # sphere\n\n");
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const Vec3 c = packing.centers[i];
        fmt::format_to(std::back_inserter(out), "{} 1 {} {} {} {} {}\n", i + 1,
                       2.0 * packing.radii[i], density, c.x, c.y, c.z);
    }
    return fmt::to_string(out);
}

std::string particles_vtu(const Packing& packing) {
    const std::size_t n = packing.size();
    fmt::memory_buffer out;
    auto put = [&]<class... Args>(fmt::format_string<Args...> format, Args&&... args) {
        fmt::format_to(std::back_inserter(out), format, std::forward<Args>(args)...);
    };
    put("<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
        "  <UnstructuredGrid>\n"
        "    <Piece NumberOfPoints=\"{0}\" NumberOfCells=\"{0}\">\n"
        "      <PointData Scalars=\"radius\">\n"
        "        <DataArray type=\"Float64\" Name=\"radius\" format=\"ascii\">\n",
        n);
    for (const double r : packing.radii)
        put("{}\n", r);
    put("        </DataArray>\n"
        "        <DataArray type=\"Float64\" Name=\"diameter\" format=\"ascii\">\n");
    for (const double r : packing.radii)
        put("{}\n", 2.0 * r);
    put("        </DataArray>\n"
        "      </PointData>\n"
        "      <Points>\n"
        "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    for (const Vec3& c : packing.centers)
        put("{} {} {}\n", c.x, c.y, c.z);
    put("        </DataArray>\n"
        "      </Points>\n"
        "      <Cells>\n"
        "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    for (std::size_t i = 0; i < n; ++i)
        put("{}\n", i);
    put("        </DataArray>\n"
        "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    for (std::size_t i = 1; i <= n; ++i)
        put("{}\n", i);
    put("        </DataArray>\n"
        "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for (std::size_t i = 0; i < n; ++i)
        put("1\n"); // VTK_VERTEX
    put("        </DataArray>\n"
        "      </Cells>\n"
        "    </Piece>\n"
        "  </UnstructuredGrid>\n"
        "</VTKFile>\n");
    return fmt::to_string(out);
}

namespace {

/// A CSV of profile bins: `header`, then per bin the mid-point, the mid-point measured as
/// `scaled(mid)`, and the value.
template <class F>
std::string profile_csv(std::string_view header, const std::vector<ProfileBin>& bins, F scaled) {
    fmt::memory_buffer out;
    fmt::format_to(std::back_inserter(out), "{}\n", header);
    for (const auto& b : bins) {
        const double mid = 0.5 * (b.low + b.high);
        // Positions to 12 significant digits: the bin centre of shell 123 of 0.02 Dp is 2.47,
        // not the 2.4699999999999998 its floating-point sum gives; values as computed.
        fmt::format_to(std::back_inserter(out), "{:.12g},{:.12g},{}\n", mid, scaled(mid), b.value);
    }
    return fmt::to_string(out);
}

} // namespace

std::vector<std::pair<std::string, std::string>> analysis_tables(const BedAnalysis& a,
                                                                 double container_radius) {
    const double dp = a.diameter;
    auto from_wall = [&](double r) { return (container_radius - r) / dp; };
    auto in_dp = [&](double length) { return length / dp; };
    std::string coordination = "contacts,spheres\n";
    for (std::size_t k = 0; k < a.coordination.histogram.size(); ++k)
        coordination += fmt::format("{},{}\n", k, a.coordination.histogram[k]);
    return {
        {"radial_void_fraction.csv", profile_csv("radial_position,x_from_wall_d,void_fraction",
                                                 a.radial_void_fraction, from_wall)},
        {"axial_void_fraction.csv",
         profile_csv("z,z_d,void_fraction", a.axial_void_fraction, in_dp)},
        {"radial_centre_distribution.csv",
         profile_csv("radial_position,x_from_wall_d,relative_density", a.centre_distribution,
                     from_wall)},
        {"coordination.csv", coordination},
        {"pair_correlation.csv", profile_csv("distance,distance_d,g", a.pair_correlation, in_dp)},
    };
}

} // namespace packbed
