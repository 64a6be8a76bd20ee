#include "magFoam/ControlDict.hpp"

namespace mag {

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
    c.maxDeltaT = d.get<double>("maxDeltaT", 100.0 * c.deltaT);
    c.minDeltaT = d.get<double>("minDeltaT", 1e-3 * c.deltaT);
    if (!(c.minDeltaT > 0)) d.fail("minDeltaT", "must be > 0 (seconds)");
    if (!(c.maxDeltaT >= c.minDeltaT)) d.fail("maxDeltaT", "must be >= minDeltaT (seconds)");
    d.reportUnused();
    return c;
}

} // namespace mag
