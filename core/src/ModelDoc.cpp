#include "magFoam/ModelDoc.hpp"

#include "magFoam/AppliedField.hpp"
#include "magFoam/Error.hpp"
#include "magFoam/FieldEvaluator.hpp"
#include "magFoam/InductionModel.hpp"
#include "magFoam/Log.hpp"
#include "magFoam/Plugins.hpp"
#include "magFoam/RigidBodyBackend.hpp"

#include <algorithm>
#include <exception>
#include <map>
#include <memory>
#include <sstream>

namespace mag::plugins {

namespace {

// Where a registry's dictionary lives in a case, and how an example nests there.
struct RegistryInfo {
    std::string key, title, where, nest; // nest: the mapping key the example sits under ("" top level)
};

const RegistryInfo& infoFor(const std::string& key) {
    static const std::vector<RegistryInfo> infos = {
        {"field", "field evaluator", "system/magSchemes.yaml, field: {type: ...}", "field"},
        {"induction", "induction model", "system/magSchemes.yaml, induction: {type: ...}", "induction"},
        {"rigidBody", "rigid-body backend", "constant/rigidBody.yaml, type: ... (the whole file)", ""},
        {"appliedField", "applied field", "constant/appliedField.yaml, type: ... (the whole file)", ""}};
    for (const auto& i : infos)
        if (i.key == key) return i;
    throw std::logic_error("no registry " + key);
}

// Quiets the models' construction logs while -doc builds them.
struct QuietLog {
    spdlog::level::level_enum saved = spdlog::get_level();
    QuietLog() { spdlog::set_level(spdlog::level::err); }
    ~QuietLog() { spdlog::set_level(saved); }
};

bool under(const std::string& path, const std::string& parent) {
    return path.size() > parent.size() && path.compare(0, parent.size(), parent) == 0 && path[parent.size()] == '.';
}

std::string indent(const std::string& text, const std::string& pad) {
    std::string out, line;
    std::istringstream in(text);
    while (std::getline(in, line)) out += pad + line + "\n";
    return out;
}

std::string valueText(const KeyRecord& r) {
    std::string type = r.type.empty() ? "any value (only its presence is checked)" : r.type;
    if (!r.words.empty()) {
        type += ":";
        for (std::size_t i = 0; i < r.words.size(); ++i) type += (i ? " | " : " ") + r.words[i];
    }
    if (!r.selected.empty()) type = "mapping: a " + r.selected + " selected by its type";
    std::string when;
    if (r.checked && r.fallback.empty()) when = "optional, not set by default";
    else if (r.required) when = "required";
    else when = "default " + r.fallback;
    return type + "; " + when;
}

template <class Base>
TypeDocumentation describe(const std::string& registryKey, const std::string& name,
                           const typename Registry<Base>::Entry& entry) {
    const RegistryInfo& info = infoFor(registryKey);
    TypeDocumentation doc{registryKey, name, entry.library, entry.doc.summary, {}, {}, {}, {}, ""};
    std::vector<std::string> examples = entry.doc.examples;
    if (examples.empty()) examples.push_back("type: " + name);

    std::vector<KeyRecord> merged;
    for (std::size_t i = 0; i < examples.size(); ++i) {
        auto log = std::make_shared<KeyLog>();
        try {
            QuietLog quiet;
            const Dict d = Dict::recording(examples[i], name + " example " + std::to_string(i + 1), log);
            (void)Base::New(d);
        } catch (const std::exception& e) {
            doc.failures.push_back("example " + std::to_string(i + 1) + ": " + e.what());
        }
        for (const KeyRecord& r : log->records) {
            auto it = std::find_if(merged.begin(), merged.end(), [&](const KeyRecord& m) { return m.path == r.path; });
            if (it == merged.end()) {
                merged.push_back(r);
                continue;
            }
            // Another example read it too: keep what each saw.
            if (it->type.empty()) it->type = r.type;
            if (it->fallback.empty()) it->fallback = r.fallback;
            it->required = it->required && r.required;
            it->checked = it->checked || r.checked;
            if (it->words.empty()) it->words = r.words;
            if (it->selected.empty()) it->selected = r.selected;
        }
    }
    std::vector<std::string> nested;
    for (const KeyRecord& r : merged)
        if (!r.selected.empty()) nested.push_back(r.path);
    for (const KeyRecord& r : merged) {
        if (r.path == "type") continue;
        if (std::any_of(nested.begin(), nested.end(), [&](const std::string& p) { return under(r.path, p); })) continue;
        doc.keys.push_back(r);
    }
    // Reading order, but a mapping's keys right after it (examples read
    // different branches, so a later example may add a key to an early mapping).
    std::map<std::string, std::size_t> firstOfTop;
    for (std::size_t i = 0; i < doc.keys.size(); ++i)
        firstOfTop.emplace(doc.keys[i].path.substr(0, doc.keys[i].path.find('.')), i);
    auto top = [&](const KeyRecord& r) { return firstOfTop.at(r.path.substr(0, r.path.find('.'))); };
    std::stable_sort(doc.keys.begin(), doc.keys.end(),
                     [&](const KeyRecord& a, const KeyRecord& b) { return top(a) < top(b); });

    std::map<std::string, const KeyDoc*> described;
    for (const KeyDoc& k : entry.doc.keys) described[k.key] = &k;
    for (const KeyRecord& r : doc.keys)
        if (!described.count(r.path)) doc.undocumented.push_back(r.path);
    for (const KeyDoc& k : entry.doc.keys)
        if (std::none_of(doc.keys.begin(), doc.keys.end(), [&](const KeyRecord& r) { return r.path == k.key; }))
            doc.unread.push_back(k.key);

    std::ostringstream os;
    os << name << ": " << info.title << " (" << entry.library << ")\n";
    os << "  in " << info.where << "\n";
    if (!entry.doc.summary.empty()) os << "\n" << indent(entry.doc.summary, "  ");
    os << "\nKeys (" << doc.keys.size() << "):\n";
    if (doc.keys.empty()) os << "  (none besides type)\n";
    for (const KeyRecord& r : doc.keys) {
        const auto it = described.find(r.path);
        os << "  " << r.path << "\n      " << valueText(r);
        if (it != described.end()) {
            if (!it->second->unit.empty() && it->second->unit != "-") os << "; unit " << it->second->unit;
            os << "\n" << indent(it->second->meaning, "      ");
        } else {
            os << "\n      (not described)\n";
        }
    }
    for (const auto& k : doc.unread) os << "  " << k << "\n      (described, but the examples never read it)\n";
    os << "\nExample:\n";
    if (info.nest.empty()) os << indent(examples.front(), "  ");
    else os << "  " << info.nest << ":\n" << indent(examples.front(), "    ");
    for (const auto& f : doc.failures) os << "\n(this example does not build: " << f << ")\n";
    doc.text = os.str();
    return doc;
}

template <class Base> void describeAll(const std::string& key, std::vector<TypeDocumentation>& out) {
    for (const auto& [name, entry] : Base::registry().entries()) out.push_back(describe<Base>(key, name, entry));
}

} // namespace

std::vector<TypeDocumentation> documentAll() {
    loadStandardModules();
    std::vector<TypeDocumentation> out;
    describeAll<FieldEvaluator>("field", out);
    describeAll<InductionModel>("induction", out);
    describeAll<RigidBodyBackend>("rigidBody", out);
    describeAll<AppliedField>("appliedField", out);
    return out;
}

std::string documentAllMarkdown() {
    std::ostringstream os;
    os << "# Model keys\n\n"
          "Every model type's keys, as `-doc TYPE` of any app prints them: the keys, value types and\n"
          "defaults are recorded from the code reading each type's examples, so they cannot drift.\n"
          "This file is `magFoam -doc all`; `etc/makeModelDoc` rewrites it and a test checks it.\n";
    for (const TypeDocumentation& d : documentAll())
        os << "\n## " << d.name << " (" << infoFor(d.registry).title << ")\n\n```text\n" << d.text << "```\n";
    return os.str();
}

std::string documentType(const std::string& name) {
    if (name == "all") return documentAllMarkdown();
    std::string text, names;
    for (const TypeDocumentation& d : documentAll()) {
        if (d.name == name) text += (text.empty() ? "" : "\n") + d.text;
        names += (names.empty() ? "" : ", ") + d.name;
    }
    if (text.empty()) throw InputError("-doc: no model type '" + name + "'; valid types: " + names + " (or all)");
    return text;
}

std::string documentIndex() {
    std::ostringstream os;
    std::string last;
    for (const TypeDocumentation& d : documentAll()) {
        if (d.registry != last) {
            const RegistryInfo& info = infoFor(d.registry);
            os << (last.empty() ? "" : "\n") << info.title << "s, in " << info.where << ":\n";
            last = d.registry;
        }
        std::string first = d.summary.substr(0, d.summary.find('\n'));
        os << "  " << d.name << std::string(d.name.size() < 10 ? 10 - d.name.size() : 1, ' ') << first << "\n";
    }
    os << "\n-doc TYPE prints a type's keys, their types, defaults, units and an example;\n"
          "-doc all every type's (docs/model-keys.md).\n";
    return os.str();
}

} // namespace mag::plugins
