#include "magFoam/Material.hpp"

#include "magFoam/Log.hpp"

#include "magFoam/Error.hpp"

namespace mag {

double Material::property(const std::string& key) const {
    const auto it = properties.find(key);
    if (it == properties.end()) {
        if (dict) dict->failHere("soft material '" + name + "' needs key '" + key + "'");
        throw InputError("material '" + name + "': soft material needs key '" + key + "'");
    }
    return it->second;
}

double Material::property(const std::string& key, double fallback) const {
    const auto it = properties.find(key);
    return it == properties.end() ? fallback : it->second;
}

void Material::fail(const std::string& key, const std::string& message) const {
    if (dict && dict->has(key)) dict->fail(key, message);
    if (dict) dict->failHere(key + ": " + message);
    throw InputError("material '" + name + "': " + key + ": " + message);
}

Material Material::read(const std::string& name, const Dict& d) {
    Material m;
    m.name = name;
    m.dict = d;
    const std::string model = d.getWord("model", {"permanent", "soft"});
    m.model = model == "soft" ? Model::soft : Model::permanent;
    m.density = d.get<double>("density");
    if (m.density <= 0) d.fail("density", "density must be positive (kg/m^3), got " + std::to_string(m.density));
    // Plausibility (warnings; docs/case-reference.md#plausibility): solids lie
    // between ~100 (foams) and ~22,600 kg/m^3 (osmium).
    if (m.density < 100)
        d.warn("density", fmt::format("{:g} kg/m^3 is lighter than any solid magnet or steel: in g/cm^3? "
                                      "({:g} g/cm^3 = {:g} kg/m^3)", m.density, m.density, 1000 * m.density));
    else if (m.density > 25000)
        d.warn("density", fmt::format("{:g} kg/m^3 is denser than any solid: in g/m^3 or mg/cm^3?", m.density));
    if (m.model == Model::permanent) {
        m.Br = d.get<double>("Br");
        if (m.Br < 0) d.fail("Br", "remanence Br must be >= 0 (tesla); reverse the magnetization direction instead");
        if (m.Br > 2.5)
            d.warn("Br", fmt::format("{:g} T is above any magnet's remanence (NdFeB: up to ~1.5 T): in mT? "
                                     "({:g} mT = {:g} T)", m.Br, m.Br, 1e-3 * m.Br));
        d.reportUnused();
    } else {
        // The induction model checks these (names, ranges) when it meets the body.
        for (const auto& key : d.keys())
            if (key != "model" && key != "density") {
                // Numbers, and switches (true/false as 1/0) such as demag's saturation.
                const YAML::Node v = d.node()[key];
                const std::string word = v.IsScalar() ? v.Scalar() : "";
                const bool flag = word == "true" || word == "false" || word == "yes" || word == "no";
                m.properties[key] = flag ? (d.get<bool>(key) ? 1.0 : 0.0) : d.get<double>(key);
            }
        if (const auto js = m.properties.find("Js"); js != m.properties.end() && js->second > 2.5)
            d.warn("Js", fmt::format("{:g} T is above any iron's saturation polarization (~2.4 T at most): in mT? "
                                     "({:g} mT = {:g} T)", js->second, js->second, 1e-3 * js->second));
    }
    return m;
}

std::map<std::string, Material> readMaterials(const Dict& dict) {
    std::map<std::string, Material> out;
    for (const auto& name : dict.keys()) out.emplace(name, Material::read(name, dict.sub(name)));
    return out;
}

} // namespace mag
