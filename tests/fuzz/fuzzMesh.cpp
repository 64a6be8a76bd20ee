// Fuzz target: one mesh reader, chosen at compile time (MAG_FUZZ_FORMAT, e.g.
// ".ply"). Any input must end in a mesh or an InputError; an accepted mesh
// must have valid indices and finite coordinates (else the target aborts).
// What a case does next, the topology checks (closed, manifold, oriented,
// embedded, shells nested right), runs on every accepted mesh too.
#include <magFoam/Error.hpp>
#include <magFoam/MeshIO.hpp>
#include <magFoam/MeshTopology.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#ifndef MAG_FUZZ_FORMAT
#error "define MAG_FUZZ_FORMAT, e.g. \".ply\""
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        const mag::SurfaceMesh mesh =
            mag::prepareSurfaceMesh(mag::parseMeshBytes(bytes, "fuzz" MAG_FUZZ_FORMAT, MAG_FUZZ_FORMAT));
        for (const auto& t : mesh.triangles)
            for (int v : t)
                if (v < 0 || v >= mesh.nVertices()) std::abort();
        for (const mag::Vec3& p : mesh.vertices)
            if (!p.allFinite()) std::abort();
        const mag::TopologyReport report = mag::checkTopology(mesh);
        (void)report.usable();
    } catch (const mag::InputError&) {
    }
    return 0;
}
