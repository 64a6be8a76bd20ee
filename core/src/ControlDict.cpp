#include "magFoam/ControlDict.hpp"

#include "magFoam/Log.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace mag {

namespace {

std::string g(double x) { return fmt::format("{:.6g}", x); }

// The times of a run must be distinct and exactly reachable: at most
// maxSteps steps of deltaT to the largest time (so t + deltaT != t and the
// step counts fit), and with fixed steps a whole number of them from
// startTime to endTime (otherwise the last step would end before or after
// endTime).
void checkTimeAxis(const Dict& d, const ControlDict& c) {
    const double reach = std::max(std::abs(c.startTime), std::abs(c.endTime));
    if (reach / c.deltaT > ControlDict::maxSteps) {
        const std::string key = std::abs(c.endTime) >= std::abs(c.startTime) ? "endTime" : "startTime";
        d.fail(key, fmt::format("a time of {} s is {} steps of deltaT {} s; at most 1e12 steps of deltaT from time "
                                "0 keep every step's time exact", g(reach), g(reach / c.deltaT), g(c.deltaT)));
    }
    if (c.adjustTimeStep) return;  // adaptive steps end on endTime exactly
    const double steps = (c.endTime - c.startTime) / c.deltaT;
    const double n = std::round(steps);
    // The rounding of the times themselves: a few ulp of the largest, in steps.
    if (std::abs(steps - n) <= 1e-6 + 4 * DBL_EPSILON * reach / c.deltaT) return;
    const double down = std::floor(steps), up = std::ceil(steps), span = c.endTime - c.startTime;
    std::string options = "deltaT " + g(span / up) + " (" + g(up) + " steps)";
    if (down >= 1) options = "deltaT " + g(span / down) + " (" + g(down) + " steps) or " + options;
    d.fail("deltaT", fmt::format("deltaT {} s does not divide the run from startTime {} s to endTime {} s ({} "
                                 "steps): fixed steps would not end on endTime. Use {}, an endTime of {} or {} s, "
                                 "or adjustTimeStep: true",
                                 g(c.deltaT), g(c.startTime), g(c.endTime), fmt::format("{:.9g}", steps), options,
                                 g(c.startTime + std::max(down, 1.0) * c.deltaT), g(c.startTime + up * c.deltaT)));
}

// Fixed steps are written every writeInterval / deltaT steps: a whole number
// of them, or the written times would not be the ones asked for.
void checkWriteInterval(const Dict& d, const ControlDict& c) {
    if (c.adjustTimeStep) return;  // adaptive steps end on every write time exactly
    const double steps = c.writeInterval / c.deltaT;
    if (steps > ControlDict::maxSteps) return;  // never written but at the end
    const double n = std::round(steps);
    if (n >= 1 && std::abs(steps - n) <= 1e-6 * n) return;
    const double down = std::max(1.0, std::floor(steps)), up = std::max(1.0, std::ceil(steps));
    std::string options = "writeInterval " + g(up * c.deltaT);
    if (down != up) options = "writeInterval " + g(down * c.deltaT) + " or " + g(up * c.deltaT);
    d.fail("writeInterval", fmt::format("writeInterval {} s is {} steps of deltaT {} s: fixed steps are written "
                                        "every whole number of steps. Use {} s, or adjustTimeStep: true",
                                        g(c.writeInterval), fmt::format("{:.9g}", steps), g(c.deltaT), options));
}

} // namespace

ControlDict ControlDict::read(const Dict& d) {
    ControlDict c;
    c.startTime = d.get<double>("startTime", 0.0);
    c.endTime = d.get<double>("endTime");
    c.deltaT = d.get<double>("deltaT");
    c.writeInterval = d.get<double>("writeInterval", c.deltaT);
    c.startFrom = d.getWord("startFrom", {"startTime", "latestTime"}, "startTime");
    c.libs = d.get<std::vector<std::string>>("libs", {});
    c.threads = d.get<int>("threads", 1);
    if (d.has("audit")) {
        const Dict a = d.sub("audit");
        c.audit.energyRise = a.get<double>("energyRise", c.audit.energyRise);
        c.audit.travel = a.get<double>("travel", c.audit.travel);
        c.audit.strict = a.get<bool>("strict", c.audit.strict);
        if (!(c.audit.energyRise > 0)) a.fail("energyRise", "must be > 0 (a fraction of the peak kinetic energy)");
        if (!(c.audit.travel > 0)) a.fail("travel", "must be > 0 (a fraction of the body's smallest dimension)");
        a.reportUnused();
    }
    if (c.deltaT <= 0) d.fail("deltaT", "time step must be positive (seconds)");
    if (c.endTime < c.startTime) d.fail("endTime", "endTime must not be before startTime");
    if (c.writeInterval <= 0) d.fail("writeInterval", "write interval must be positive (simulated seconds)");
    if (c.threads < 0) d.fail("threads", "threads must be >= 0 (0 = all cores)");
    c.adjustTimeStep = d.get<bool>("adjustTimeStep", false);
    c.implicitTorque = d.getWord("magneticStiffness", {"explicit", "implicit"}, "explicit") == "implicit";
    checkTimeAxis(d, c);
    checkWriteInterval(d, c);
    c.maxDeltaT = d.get<double>("maxDeltaT", 100.0 * c.deltaT);
    c.minDeltaT = d.get<double>("minDeltaT", 1e-3 * c.deltaT);
    if (!(c.minDeltaT > 0)) d.fail("minDeltaT", "must be > 0 (seconds)");
    if (!(c.maxDeltaT >= c.minDeltaT)) d.fail("maxDeltaT", "must be >= minDeltaT (seconds)");
    d.reportUnused();
    return c;
}

} // namespace mag
