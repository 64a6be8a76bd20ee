#include "magFoam/ContactSettings.hpp"

#include <algorithm>
#include <cmath>

namespace mag {

ContactSettings ContactSettings::read(const Dict& d, const Dict& c) {
    ContactSettings s;
    s.gravity = d.get<Vec3>("gravity", Vec3::Zero());
    if (d.has("ground")) {
        const Dict g = d.sub("ground");
        s.groundHeight = g.get<double>("height", 0.0);
        g.reportUnused();
    }
    s.friction = c.get<double>("friction", 0.5);
    if (!(s.friction >= 0)) c.fail("friction", "friction coefficient must be >= 0");
    s.rollingFriction = c.get<double>("rollingFriction", 0.0);
    if (!(s.rollingFriction >= 0)) c.fail("rollingFriction", "rollingFriction must be >= 0 (m: torque per normal force)");
    s.spinningFriction = c.get<double>("spinningFriction", 0.0);
    if (!(s.spinningFriction >= 0))
        c.fail("spinningFriction", "spinningFriction must be >= 0 (m: torque per normal force)");
    s.restitution = c.get<double>("restitution", 0.1);
    if (!(s.restitution >= 0 && s.restitution <= 1)) c.fail("restitution", "restitution must be in [0, 1]");
    s.bounceVelocity = c.get<double>("bounceVelocity", 0.1);
    if (!(s.bounceVelocity >= 0)) c.fail("bounceVelocity", "bounceVelocity must be >= 0 (m/s)");
    s.erp = c.get<double>("erp", 0.2);
    if (!(s.erp > 0 && s.erp <= 1)) c.fail("erp", "erp must be in (0, 1]");
    s.surfaceLayer = c.get<double>("surfaceLayer", 1e-6);
    if (!(s.surfaceLayer >= 0)) c.fail("surfaceLayer", "surfaceLayer must be >= 0 (m)");
    s.subSteps = d.get<int>("subSteps", 1);
    if (s.subSteps < 1 || s.subSteps > 10000) d.fail("subSteps", "subSteps must be 1..10000");
    s.maxTravel = d.get<double>("maxTravel", 0.1);
    if (!(s.maxTravel >= 0)) d.fail("maxTravel", "maxTravel must be >= 0 (0: fixed subSteps)");
    s.maxSubSteps = d.get<int>("maxSubSteps", 1000);
    if (s.maxSubSteps < s.subSteps || s.maxSubSteps > 100000)
        d.fail("maxSubSteps", "maxSubSteps must be subSteps..100000");
    return s;
}

int ContactSettings::subStepsFor(double worstTravel) const {
    if (maxTravel <= 0) return subSteps;
    const double wanted = std::ceil(worstTravel / maxTravel);
    return wanted > subSteps ? static_cast<int>(std::min<double>(wanted, maxSubSteps)) : subSteps;
}

} // namespace mag
