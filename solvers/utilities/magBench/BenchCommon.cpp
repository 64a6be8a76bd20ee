#include "BenchCommon.hpp"

#include "oracles/akounYonnet.hpp"

#include <magFoam/Error.hpp>
#include <magFoam/MeshPrimitives.hpp>
#include <magFoam/ShapeFactory.hpp>

#include <cstdlib>
#include <map>

#include <fmt/format.h>

namespace mag::bench {

Body cube(const std::string& name, double edge, double Br, const Vec3& position, const Quat& q) {
    // One shape per edge length: evaluators cache their tables per shape.
    static std::map<double, std::shared_ptr<const Shape>> shapes;
    auto& shape = shapes[edge];
    if (!shape) {
        ShapeKind kind;
        kind.kind = ShapeKind::Kind::box;
        kind.size = Vec3::Constant(edge);
        shape = makeShape(makeBox(kind.size), kind);
    }
    Body b;
    b.name = name;
    b.shape = shape;
    b.material.Br = Br;
    b.material.density = 7500;
    b.magnetizationBody = Vec3(0, 0, Br / mu0);
    b.position = position;
    b.orientation = q;
    return b;
}

std::vector<Body> cubePair(double gap) {
    return {cube("bottom", 0.01, 1.0, Vec3::Zero()), cube("top", 0.01, 1.0, Vec3(0, 0, 0.01 + gap))};
}

std::unique_ptr<FieldEvaluator> evaluator(const std::string& yaml) {
    return FieldEvaluator::New(Dict::fromString(yaml, "magBench"));
}

Vec3 exactCubeForce(const Body& lower, const Body& upper) {
    const Vec3 s1 = Vec3::Constant(std::cbrt(lower.shape->volume));
    const Vec3 s2 = Vec3::Constant(std::cbrt(upper.shape->volume));
    return oracle::akounYonnetForce(s1, lower.position, s2, upper.position, lower.material.Br, upper.material.Br);
}

std::filesystem::path scratchCase(const std::filesystem::path& src, const std::filesystem::path& dst,
                                  const std::string& what) {
    std::filesystem::remove_all(dst);
    std::filesystem::create_directories(dst);
    for (const char* sub : {"constant", "system"})
        std::filesystem::copy(src / sub, dst / sub, std::filesystem::copy_options::recursive);
    if (!std::filesystem::exists(src / "system/geometryDict.yaml")) return dst;
    std::error_code ec;
    const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) throw std::runtime_error(what + ": cannot find this executable's folder (/proc/self/exe)");
    const std::string cmd = fmt::format("'{}' -case '{}' > '{}' 2>&1", (self.parent_path() / "magMakeGeometry").string(),
                                        dst.string(), (dst / "log.magMakeGeometry").string());
    if (std::system(cmd.c_str()) != 0)
        throw std::runtime_error(what + ": magMakeGeometry failed in " + dst.string() + " (see log.magMakeGeometry there)");
    return dst;
}

} // namespace mag::bench
