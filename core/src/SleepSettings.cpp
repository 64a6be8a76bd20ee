#include "magFoam/SleepSettings.hpp"

#include <string>

namespace mag {

SleepSettings SleepSettings::read(const Dict& rigidBody) {
    SleepSettings s;
    if (!rigidBody.has("sleep")) return s;
    const Dict d = rigidBody.sub("sleep");
    s.enabled = d.get<bool>("enabled", true);
    s.speed = d.get<double>("speed", s.speed);
    s.time = d.get<double>("time", s.time);
    s.wrenchChange = d.get<double>("wrenchChange", s.wrenchChange);
    s.margin = d.get<double>("margin", s.margin);
    const std::string islands = d.get<std::string>("islands", "contacts");
    if (islands == "contacts") s.islands = Islands::contacts;
    else if (islands == "boundingSpheres") s.islands = Islands::boundingSpheres;
    else d.fail("islands", "unknown '" + islands + "': expected contacts or boundingSpheres");
    if (!(s.speed > 0)) d.fail("speed", "must be > 0 (m/s: a body is calm below it)");
    if (!(s.time >= 0)) d.fail("time", "must be >= 0 (seconds calm before sleeping)");
    if (!(s.wrenchChange > 0)) d.fail("wrenchChange", "must be > 0 (a relative change of the magnetic wrench)");
    if (!(s.margin >= 0)) d.fail("margin", "must be >= 0 (a fraction of the smaller bounding radius)");
    d.reportUnused();
    return s;
}

} // namespace mag
