#include "ForceSweep.hpp"

#include <magFoam/Error.hpp>
#include <magFoam/InputFile.hpp>
#include <magFoam/Log.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>

namespace mag::forces {

namespace {

void readRange(const Dict& d, Sweep& s) {
    s.from = d.get<double>("from");
    s.to = d.get<double>("to");
    s.steps = d.get<int>("steps");
    if (s.steps < 1) d.fail("steps", "steps (the number of evaluations, from and to included) must be >= 1");
    // As for orientation.angle in bodies.yaml (docs/case-reference.md#plausibility).
    for (const char* key : {"from", "to"}) {
        const double angle = d.get<double>(key), k = angle / (pi / 12);
        if (s.rotate && angle != std::round(angle) && std::abs(angle) <= 2 * pi + 1e-9 && std::round(k) != 0 &&
            std::abs(k - std::round(k)) < 1e-3 * std::abs(k))
            d.warn(key, fmt::format("{:g} looks like radians ({:g} rad = {:g} deg); angles here are in degrees",
                                    angle, angle, angle * 180 / pi));
    }
}

Sweep readSweep(const Case& c, const Dict& dict) {
    Sweep s;
    const Dict d = dict.sub("sweep");
    s.body = c.bodyIndex(d.get<std::string>("body"), d.where("body") + ": sweep.body");
    const std::string forms = "a translation {body, direction, from, to, steps} or a rotation "
                              "{body, rotate: {axis, from, to, steps}}";
    std::string translationKey;
    for (const char* k : {"direction", "from", "to", "steps"})
        if (translationKey.empty() && d.has(k)) translationKey = k;
    s.rotate = d.has("rotate");
    if (s.rotate && !translationKey.empty())
        d.fail(translationKey, "a sweep is " + forms + ", not both; with rotate, from, to and steps go inside it");
    if (!s.rotate && translationKey.empty()) d.failHere("expected " + forms);
    const Dict r = s.rotate ? d.sub("rotate") : d;
    const std::string dirKey = s.rotate ? "axis" : "direction";
    s.direction = r.get<Vec3>(dirKey);
    if (!(s.direction.stableNorm() > 0)) r.fail(dirKey, "sweep " + dirKey + " has zero length");
    s.direction.stableNormalize();
    readRange(r, s);
    r.reportUnused();
    d.reportUnused();
    dict.reportUnused();
    return s;
}

} // namespace

std::optional<Sweep> readForcesDict(const Case& c) {
    const auto file = c.dir() / "system/forcesDict.yaml";
    if (!inputPresent(file)) return std::nullopt; // a dangling link is present: its error names it
    return readSweep(c, Dict::fromFile(file));
}

double evaluate(std::vector<Body>& bodies, const MagneticSystem& system, const std::optional<Sweep>& sweep,
                const std::function<void(const Evaluation&)>& onEvaluation) {
    const int steps = sweep ? sweep->steps : 1;
    const Vec3 start = sweep ? bodies[sweep->body].position : Vec3::Zero();
    const Quat startOrientation = sweep ? bodies[sweep->body].orientation : Quat::Identity();
    double seconds = 0;
    for (int k = 0; k < steps; ++k) {
        double offset = 0;  // m, or degrees for a rotation
        if (sweep) {
            offset = steps == 1 ? sweep->from : sweep->from + (sweep->to - sweep->from) * k / (steps - 1);
            Body& b = bodies[sweep->body];
            if (sweep->rotate)  // about the world axis through the centre of mass: the position stays
                b.orientation =
                    (Quat(Eigen::AngleAxisd(offset * pi / 180.0, sweep->direction)) * startOrientation).normalized();
            else
                b.position = start + offset * sweep->direction;
        }
        const auto t0 = std::chrono::steady_clock::now();
        const InductionReport ind = system.converge(bodies);
        if (!ind.converged) {
            std::string names;
            for (const auto& n : ind.unconverged) names += " " + n;
            spdlog::warn("induction did not converge ({} iterations, residual {:.3g}):{}", ind.iterations,
                         ind.residual, names);
        }
        const std::vector<Wrench> w = system.wrenches(bodies);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

        onEvaluation(Evaluation{k, offset, bodies, w});
    }
    return seconds;
}

} // namespace mag::forces
