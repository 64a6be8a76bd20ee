#include "magFoam/Material.hpp"

namespace mag {

Material Material::read(const std::string& name, const Dict& d) {
    Material m;
    m.name = name;
    const std::string model = d.getWord("model", {"permanent", "soft"});
    m.model = model == "soft" ? Model::soft : Model::permanent;
    m.density = d.get<double>("density");
    if (m.density <= 0) d.fail("density", "density must be positive (kg/m^3), got " + std::to_string(m.density));
    if (m.model == Model::permanent) {
        m.Br = d.get<double>("Br");
        if (m.Br < 0) d.fail("Br", "remanence Br must be >= 0 (tesla); reverse the magnetization direction instead");
    } else {
        m.k = d.get<double>("k");
        if (m.k <= 0) d.fail("k", "induction control k must be positive");
        m.Js = d.get<double>("Js");
        if (m.Js <= 0) d.fail("Js", "saturation polarization Js must be positive (tesla)");
        m.alpha = d.get<double>("alpha", 0.5);
        if (m.alpha <= 0) d.fail("alpha", "LLG damping alpha must be positive");
    }
    d.reportUnused();
    return m;
}

std::map<std::string, Material> readMaterials(const Dict& dict) {
    std::map<std::string, Material> out;
    for (const auto& name : dict.keys()) out.emplace(name, Material::read(name, dict.sub(name)));
    return out;
}

} // namespace mag
