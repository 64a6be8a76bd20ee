// magEndState: where a run ended (docs/outputs.md#end-state). For the newest
// time folder (or -time T): every dynamic body's speed (of its fastest point,
// |v| + |w| R), the body nearest to it and the gap between their surfaces,
// and how deep it overlaps another body. A body is attached when its gap is at
// most -attached (default 1 mm), at rest when its speed is below -rest
// (default 1 mm/s), and sunk in when it overlaps another deeper than -depth
// (default 0.1 mm: deeper than any backend's contact layer). With -check the
// app exits 1 unless every dynamic body is attached, at rest and not sunk in:
// the paper scenes' acceptance (Figs. 8, 1, 9) in one command.
//
// Gaps and overlaps: surfaceGap and findOverlaps (BodyOverlap.hpp). For bodies
// resting in each other the gap is the contact layer (~1 um); the overlap
// column says how deep they are in each other.
#include <magFoam/ArgList.hpp>
#include <magFoam/BodyOverlap.hpp>
#include <magFoam/Case.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/OutputFile.hpp>
#include <magFoam/ResultsWriter.hpp>

#include <cmath>
#include <cstdio>
#include <limits>

using namespace mag;

namespace {

double number(const ArgList& args, const std::string& name, double fallback) {
    if (!args.found(name)) return fallback;
    const std::string text = args.get(name);
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0' || !(v >= 0) || !std::isfinite(v))
        throw InputError("-" + name + " " + text + ": expected a number >= 0");
    return v;
}

int run(const ArgList& args) {
    Case c = Case::read(args.caseDir());
    std::vector<Body>& bodies = c.bodies();
    const double attached = number(args, "attached", 1e-3), rest = number(args, "rest", 1e-3);
    const double depthLimit = number(args, "depth", 1e-4);

    std::filesystem::path folder;
    if (args.found("time")) {
        folder = c.dir() / args.get("time");
        if (!std::filesystem::exists(folder / "bodies.yaml"))
            throw InputError("-time " + args.get("time") + ": " + (folder / "bodies.yaml").string() + " not found");
    } else {
        const auto latest = latestTimeFolder(c.dir());
        if (!latest) throw InputError(c.dir().string() + ": no time folder with a bodies.yaml (run magFoam first)");
        folder = *latest;
    }
    const RestartState state = readState(folder / "bodies.yaml", bodies);

    // Overlaps deeper than the contact layers (relative tolerance: 1e-6 of the larger body).
    std::vector<double> depth(bodies.size(), 0.0);
    for (const BodyOverlap& o : findOverlaps(bodies))
        depth[o.a] = std::max(depth[o.a], o.depth), depth[o.b] = std::max(depth[o.b], o.depth);

    std::string csv;
    int dynamic = 0, nAttached = 0, nRest = 0, nSunk = 0;
    double fastest = 0;
    spdlog::info("magEndState: {} at t = {} s (step {}); attached: gap <= {} m, at rest: speed < {} m/s, sunk in: "
                 "overlap > {} m", folder.string(), state.time, state.step, attached, rest, depthLimit);
    spdlog::info("  {:<16} {:>12} {:>16} {:>12} {:>12}  state", "body", "speed m/s", "nearest", "gap m", "overlap m");
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Body& b = bodies[i];
        if (b.fixed) continue;
        ++dynamic;
        const double speed = b.velocity.norm() + b.angularVelocity.norm() * b.shape->boundingRadius;
        double gap = std::numeric_limits<double>::infinity();
        std::size_t nearest = i;
        for (std::size_t j = 0; j < bodies.size(); ++j) {
            if (j == i) continue;
            const double g = surfaceGap(b, bodies[j], gap);
            if (g < gap) gap = g, nearest = j;
        }
        const bool isAttached = gap <= attached, atRest = speed < rest, sunk = depth[i] > depthLimit;
        nAttached += isAttached, nRest += atRest, nSunk += sunk;
        fastest = std::max(fastest, speed);
        std::string status = std::string(isAttached ? "attached" : "loose") + (atRest ? ", at rest" : ", moving") +
                             (sunk ? ", SUNK IN" : "");
        const std::string other = nearest == i ? "-" : bodies[nearest].name;
        spdlog::info("  {:<16} {:>12.4g} {:>16} {:>12.4g} {:>12.4g}  {}", b.name, speed, other, gap, depth[i], status);
        char row[512];
        std::snprintf(row, sizeof row, "%s,%.10g,%s,%.10g,%.10g,%d,%d,%d\n", b.name.c_str(), speed, other.c_str(), gap,
                      depth[i], isAttached, atRest, sunk);
        csv += row;
    }
    makeFolder(c.dir() / "postProcessing");
    writeFileAtomically(c.dir() / "postProcessing/endState.csv",
                        "body,speed,nearest,gap,overlap,attached,atRest,sunkIn\n" + csv);
    const bool ok = nAttached == dynamic && nRest == dynamic && nSunk == 0;
    spdlog::info("End state: {} of {} dynamic bodies attached, {} at rest, {} sunk in; fastest point {:.3g} m/s: {}",
                 nAttached, dynamic, nRest, nSunk, fastest, ok ? "all attached and at rest" : "NOT all attached and at rest");
    return args.found("check") && !ok ? 1 : 0;
}

} // namespace

int main(int argc, char** argv) {
    ArgList args("magEndState", "Where a run ended: each dynamic body's speed, nearest body, gap and overlap, for the "
                                "newest time folder; -check exits 1 unless every one is attached and at rest.");
    args.option("time", "T", "the time folder to read (default: the newest)")
        .option("attached", "GAP", "largest gap to another body that counts as attached, m (default 1e-3)")
        .option("rest", "SPEED", "speed of the fastest point below which a body is at rest, m/s (default 1e-3)")
        .option("depth", "DEPTH", "overlap deeper than this is sunk in, m (default 1e-4)")
        .option("check", "", "exit 1 unless every dynamic body is attached, at rest and not sunk in");
    args.outputs(R"(  postProcessing/endState.csv   one row per dynamic body:
      body, speed [m/s] (|v| + |w| R), nearest (body), gap [m], overlap [m] (deepest into another body),
      attached, atRest, sunkIn (0/1)
)");
    if (!args.parse(argc, argv)) return args.exitCode();
    return runGuarded(args, run);
}
