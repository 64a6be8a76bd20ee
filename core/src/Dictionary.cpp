#include "magFoam/Dictionary.hpp"

#include "magFoam/Error.hpp"
#include "magFoam/InputFile.hpp"
#include "magFoam/Log.hpp"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

namespace mag {

namespace {

std::string markText(const std::string& file, const YAML::Mark& m) {
    if (m.is_null()) return file;
    return file + ":" + std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1);
}

std::string shortText(const YAML::Node& n) {
    if (!n.IsDefined() || n.IsNull()) return "nothing";
    std::ostringstream os;
    os << n;
    std::string s = os.str();
    std::replace(s.begin(), s.end(), '\n', ' ');
    if (s.size() > 60) s = s.substr(0, 57) + "...";
    return "'" + s + "'";
}

// Levenshtein distance, for "did you mean" on misspelled keys.
std::size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        cur[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            std::size_t sub = prev[j - 1] + (std::tolower(a[i - 1]) == std::tolower(b[j - 1]) ? 0 : 1);
            cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
        }
        std::swap(prev, cur);
    }
    return prev[b.size()];
}

std::string joinWords(const std::vector<std::string>& words) {
    std::string out;
    for (const auto& w : words) out += (out.empty() ? "" : ", ") + w;
    return out;
}

// yaml-cpp keeps duplicate keys silently; a duplicate is almost always a
// copy-paste mistake, so reject it where it is.
void rejectDuplicateKeys(const YAML::Node& node, const std::string& file) {
    if (node.IsMap()) {
        std::set<std::string> seen;
        for (const auto& kv : node) {
            const std::string key = kv.first.Scalar();
            if (!seen.insert(key).second)
                throw InputError(markText(file, kv.first.Mark()) + ": duplicate key '" + key + "'");
            rejectDuplicateKeys(kv.second, file);
        }
    } else if (node.IsSequence()) {
        for (const auto& item : node) rejectDuplicateKeys(item, file);
    }
}

// Walks the parser's events before yaml-cpp builds nodes, to refuse what the
// node tree would make unbounded: an alias stands for its whole anchored node,
// so 10 levels of `&a [*a, *a, ...]` are billions of nodes to every later walk
// (or a cycle, when the alias sits inside its own anchor). Counts the nodes as
// they would be with every alias expanded, and the documents.
class YamlBudget : public YAML::EventHandler {
public:
    static constexpr std::size_t nodeLimit = 1'000'000;

    explicit YamlBudget(const std::string& file) : file_(file) {}

    void OnDocumentStart(const YAML::Mark& mark) override {
        if (++documents_ > 1)
            throw InputError(markText(file_, mark) +
                             ": a second YAML document ('---'); a dictionary is one document");
        sizes_.assign(1, 0);  // anchor ids count from 1 in each document
    }
    void OnDocumentEnd() override {}
    void OnAnchor(const YAML::Mark&, const std::string& name) override { anchorName_ = name; }
    void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override { leaf(mark, anchor); }
    void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor, const std::string&) override {
        leaf(mark, anchor);
    }
    void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
        if (anchor >= sizes_.size() || sizes_[anchor] == 0) {
            const auto open = std::find_if(open_.begin(), open_.end(), [&](const Open& o) { return o.anchor == anchor; });
            throw InputError(markText(file_, mark) + ": alias *" + (open != open_.end() ? open->name : "?") +
                             " refers to a node that contains it (an endless cycle)");
        }
        add(mark, sizes_[anchor]);
    }
    void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                         YAML::EmitterStyle::value) override {
        start(mark, anchor);
    }
    void OnSequenceEnd() override { end(); }
    void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                    YAML::EmitterStyle::value) override {
        start(mark, anchor);
    }
    void OnMapEnd() override { end(); }

private:
    struct Open {
        YAML::anchor_t anchor;
        std::string name;
        std::size_t nodes;  // this collection and everything in it so far
    };
    void anchorSize(YAML::anchor_t anchor, std::size_t nodes) {
        if (anchor == YAML::NullAnchor) return;
        if (sizes_.size() <= anchor) sizes_.resize(anchor + 1, 0);
        sizes_[anchor] = nodes;
    }
    void add(const YAML::Mark& mark, std::size_t nodes) {
        // Both terms are at most nodeLimit: no overflow.
        total_ += nodes;
        if (!open_.empty()) open_.back().nodes += nodes;
        if (total_ > nodeLimit)
            throw InputError(markText(file_, mark) + ": the dictionary expands to more than " +
                             std::to_string(nodeLimit) + " values (aliases '*name' repeat their anchored node)");
    }
    void leaf(const YAML::Mark& mark, YAML::anchor_t anchor) {
        anchorSize(anchor, 1);
        anchorName_.clear();
        add(mark, 1);
    }
    void start(const YAML::Mark& mark, YAML::anchor_t anchor) {
        add(mark, 1);
        open_.push_back({anchor, anchorName_, 1});
        anchorName_.clear();
        if (anchor != YAML::NullAnchor) anchorSize(anchor, 0);  // 0: still open
    }
    void end() {
        const Open done = open_.back();
        open_.pop_back();
        anchorSize(done.anchor, done.nodes);
        if (!open_.empty()) open_.back().nodes += done.nodes - 1;  // the 1 was added at start
    }

    const std::string& file_;
    int documents_ = 0;
    std::size_t total_ = 0;
    std::vector<std::size_t> sizes_;
    std::vector<Open> open_;
    std::string anchorName_;
};

// Every number of a dictionary (dictionaryNumberLimit, Dictionary.hpp).
bool inRange(double x) { return std::isfinite(x) && std::abs(x) <= dictionaryNumberLimit; }
const std::string rangeText = " of magnitude at most 1e30";

bool parseDouble(const YAML::Node& n, double& out) {
    if (!n.IsScalar()) return false;
    const std::string& s = n.Scalar();
    if (s.empty()) return false;
    // YAML 1.2 spellings of the special floats (rejected later as non-finite).
    std::string l = s;
    std::transform(l.begin(), l.end(), l.begin(), ::tolower);
    if (l == ".nan") return out = std::numeric_limits<double>::quiet_NaN(), true;
    if (l == ".inf" || l == "+.inf") return out = std::numeric_limits<double>::infinity(), true;
    if (l == "-.inf") return out = -std::numeric_limits<double>::infinity(), true;
    char* end = nullptr;
    errno = 0;
    out = std::strtod(s.c_str(), &end);
    return end == s.c_str() + s.size() && errno != ERANGE;
}

} // namespace

// ---------------------------------------------------------------------------

Dict::Dict()
    : state_(std::make_shared<FileState>(FileState{"<empty>", "", nullptr})), node_(YAML::NodeType::Map),
      asked_(std::make_shared<std::set<std::string>>()) {}

Dict::Dict(std::shared_ptr<const FileState> state, YAML::Node node, std::string path)
    : state_(std::move(state)), node_(std::move(node)), path_(std::move(path)),
      asked_(std::make_shared<std::set<std::string>>()) {}

Dict Dict::fromFile(const std::filesystem::path& file) {
    return fromString(readInputFile(file, dictionaryFileLimit, "dictionary"), file.string());
}

Dict Dict::fromString(const std::string& text, const std::string& name) { return recording(text, name, nullptr); }

Dict Dict::recording(const std::string& text, const std::string& name, std::shared_ptr<KeyLog> log) {
    YAML::Node root;
    try {
        // The events first (documents, alias expansion), then the tree.
        std::istringstream in(text);
        YAML::Parser parser(in);
        YamlBudget budget(name);
        while (parser.HandleNextDocument(budget)) {
        }
        root = YAML::Load(text);
    } catch (const YAML::DeepRecursion& e) {
        throw InputError(markText(name, e.mark) + ": lists or mappings nested more than " +
                         std::to_string(e.depth() - 1) + " levels deep");
    } catch (const YAML::Exception& e) {
        throw InputError(markText(name, e.mark) + ": malformed YAML: " + e.msg);
    }
    if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map); // empty file
    if (!root.IsMap())
        throw InputError(markText(name, root.Mark()) + ": expected a mapping of 'key: value' at the top level, got " +
                         shortText(root));
    rejectDuplicateKeys(root, name);
    return Dict(std::make_shared<FileState>(FileState{name, text, std::move(log)}), root, "");
}

Dict Dict::fromNode(const YAML::Node& node, const std::string& name) {
    if (!node.IsMap())
        throw InputError(name + ": expected a mapping of 'key: value' at the top level, got " + shortText(node));
    rejectDuplicateKeys(node, name);
    return Dict(std::make_shared<FileState>(FileState{name, "", nullptr}), node, "");
}

KeyRecord& KeyLog::at(const std::string& path) {
    for (auto& r : records)
        if (r.path == path) return r;
    records.push_back(KeyRecord{path, "", "", false, false, {}, ""});
    return records.back();
}

KeyRecord* Dict::record(const std::string& key) const {
    return state_->log ? &state_->log->at(keyPath(key)) : nullptr;
}

void Dict::noteSelected(const std::string& what) const {
    if (state_->log && !path_.empty()) state_->log->at(path_).selected = what;
}

std::string Dict::keyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

std::string Dict::where() const { return markText(state_->file, node_.Mark()); }

std::string Dict::where(const std::string& key) const {
    YAML::Node v = value(key);
    if (v.IsDefined()) return markText(state_->file, v.Mark());
    return where();
}

void Dict::fail(const std::string& key, const std::string& message) const {
    throw InputError(where(key) + ": " + keyPath(key) + ": " + message);
}

void Dict::warn(const std::string& key, const std::string& message) const {
    spdlog::warn("{}: {}: {}", where(key), keyPath(key), message);
}

void Dict::failHere(const std::string& message) const {
    throw InputError(where() + ": " + (path_.empty() ? std::string("") : path_ + ": ") + message);
}

YAML::Node Dict::value(const std::string& key) const {
    asked_->insert(key);
    if (!node_.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
    for (const auto& kv : node_)
        if (kv.first.Scalar() == key) return kv.second;
    return YAML::Node(YAML::NodeType::Undefined);
}

YAML::Node Dict::required(const std::string& key) const {
    YAML::Node v = value(key);
    if (!v.IsDefined()) {
        // A key of this mapping that nothing has asked for and that is spelt
        // nearly like the missing one is almost always it, misspelt.
        std::string hint;
        std::size_t best = std::max<std::size_t>(3, key.size() / 4 + 1);
        if (node_.IsMap())
            for (const auto& kv : node_) {
                const std::string k = kv.first.Scalar();
                if (asked_->count(k)) continue;
                if (const std::size_t d = editDistance(k, key); d < best) best = d, hint = k;
            }
        if (!hint.empty()) {
            YAML::Node at;
            for (const auto& kv : node_)
                if (kv.first.Scalar() == hint) at = kv.first;
            fail(key, "required key is missing; " + markText(state_->file, at.Mark()) + " has the unknown key '" +
                          hint + "': did you mean '" + key + "'?");
        }
        fail(key, "required key is missing");
    }
    return v;
}

bool Dict::has(const std::string& key) const {
    if (KeyRecord* r = record(key); r && r->type.empty()) r->checked = true;
    return value(key).IsDefined();
}
bool Dict::isMap(const std::string& key) const { return value(key).IsMap(); }
bool Dict::isList(const std::string& key) const { return value(key).IsSequence(); }

std::vector<std::string> Dict::keys() const {
    std::vector<std::string> out;
    if (node_.IsMap())
        for (const auto& kv : node_) out.push_back(kv.first.Scalar());
    return out;
}

Dict Dict::sub(const std::string& key) const {
    if (KeyRecord* r = record(key)) r->type = "mapping", r->required = true;
    YAML::Node v = required(key);
    if (!v.IsMap()) fail(key, "expected a mapping of 'key: value', got " + shortText(v));
    return Dict(state_, v, keyPath(key));
}

Dict Dict::subOrEmpty(const std::string& key) const {
    if (KeyRecord* r = record(key)) r->type = "mapping", r->fallback = "{}";
    YAML::Node v = value(key);
    if (!v.IsDefined() || v.IsNull()) return Dict(state_, YAML::Node(YAML::NodeType::Map), keyPath(key));
    if (!v.IsMap()) fail(key, "expected a mapping of 'key: value', got " + shortText(v));
    return Dict(state_, v, keyPath(key));
}

std::vector<Dict> Dict::list(const std::string& key) const {
    if (KeyRecord* r = record(key)) r->type = "list of mappings", r->required = true;
    YAML::Node v = required(key);
    if (!v.IsSequence()) fail(key, "expected a list ('- ...' items), got " + shortText(v));
    std::vector<Dict> out;
    for (std::size_t i = 0; i < v.size(); ++i) {
        const std::string p = keyPath(key) + "[" + std::to_string(i) + "]";
        if (!v[i].IsMap())
            throw InputError(markText(state_->file, v[i].Mark()) + ": " + p + ": expected a mapping, got " +
                             shortText(v[i]));
        out.push_back(Dict(state_, v[i], p));
    }
    return out;
}

void Dict::reportUnused() const {
    if (!node_.IsMap()) return;
    for (const auto& kv : node_) {
        const std::string key = kv.first.Scalar();
        if (asked_->count(key)) continue;
        std::vector<std::string> valid(asked_->begin(), asked_->end());
        std::string hint;
        std::size_t best = 3;
        for (const auto& v : valid) {
            std::size_t d = editDistance(key, v);
            if (d < best) best = d, hint = v;
        }
        std::string msg = markText(state_->file, kv.first.Mark()) + ": " +
                          (path_.empty() ? std::string("") : path_ + ": ") + "unknown key '" + key + "'";
        if (!hint.empty()) msg += " (did you mean '" + hint + "'?)";
        msg += valid.empty() ? "; this mapping takes no keys" : "; valid keys: " + joinWords(valid);
        throw InputError(msg);
    }
}

std::string Dict::getWord(const std::string& key, const std::vector<std::string>& valid) const {
    const std::string w = get<std::string>(key);
    if (std::find(valid.begin(), valid.end(), w) == valid.end())
        fail(key, "unknown value '" + w + "'; valid values: " + joinWords(valid));
    if (KeyRecord* r = record(key)) r->words = valid;
    return w;
}

std::string Dict::getWord(const std::string& key, const std::vector<std::string>& valid,
                          const std::string& fallback) const {
    const std::string w = has(key) ? getWord(key, valid) : fallback;
    if (KeyRecord* r = record(key)) r->type = "word", r->words = valid, r->fallback = fallback, r->required = false;
    return w;
}

// --- Typed conversion -------------------------------------------------------

template <class T> struct DictConvert;

template <> struct DictConvert<double> {
    static double from(const Dict& d, const std::string& key, const YAML::Node& n) {
        double x;
        if (!parseDouble(n, x)) d.fail(key, "expected a number, got " + shortText(n));
        if (!inRange(x)) d.fail(key, "expected a finite number" + rangeText + ", got " + shortText(n));
        return x;
    }
};

template <> struct DictConvert<int> {
    static int from(const Dict& d, const std::string& key, const YAML::Node& n) {
        double x;
        if (!parseDouble(n, x) || !std::isfinite(x) || x != std::floor(x) || std::abs(x) > 2e9)
            d.fail(key, "expected an integer, got " + shortText(n));
        return static_cast<int>(x);
    }
};

template <> struct DictConvert<bool> {
    static bool from(const Dict& d, const std::string& key, const YAML::Node& n) {
        if (n.IsScalar()) {
            std::string s = n.Scalar();
            std::transform(s.begin(), s.end(), s.begin(), ::tolower);
            if (s == "true" || s == "yes" || s == "on") return true;
            if (s == "false" || s == "no" || s == "off") return false;
        }
        d.fail(key, "expected true or false, got " + shortText(n));
    }
};

template <> struct DictConvert<std::string> {
    static std::string from(const Dict& d, const std::string& key, const YAML::Node& n) {
        if (!n.IsScalar()) d.fail(key, "expected a word or string, got " + shortText(n));
        return n.Scalar();
    }
};

template <> struct DictConvert<std::vector<double>> {
    static std::vector<double> from(const Dict& d, const std::string& key, const YAML::Node& n) {
        if (!n.IsSequence()) d.fail(key, "expected a list of numbers like [1, 2, 3], got " + shortText(n));
        std::vector<double> out;
        for (const auto& item : n) {
            double x;
            if (!parseDouble(item, x) || !inRange(x))
                d.fail(key, "expected a list of finite numbers" + rangeText + ", got " + shortText(n));
            out.push_back(x);
        }
        return out;
    }
};

template <> struct DictConvert<std::vector<std::vector<double>>> {
    static std::vector<std::vector<double>> from(const Dict& d, const std::string& key, const YAML::Node& n) {
        if (!n.IsSequence())
            d.fail(key, "expected a list of rows of numbers like [[1, 2], [3, 4]], got " + shortText(n));
        std::vector<std::vector<double>> out;
        for (const auto& row : n) {
            if (!row.IsSequence()) d.fail(key, "expected a list of rows like [[1, 2], [3, 4]], got " + shortText(n));
            std::vector<double> r;
            for (const auto& item : row) {
                double x;
                if (!parseDouble(item, x) || !inRange(x))
                    d.fail(key, "expected rows of finite numbers" + rangeText + ", got " + shortText(row));
                r.push_back(x);
            }
            out.push_back(std::move(r));
        }
        return out;
    }
};

template <> struct DictConvert<std::vector<std::string>> {
    static std::vector<std::string> from(const Dict& d, const std::string& key, const YAML::Node& n) {
        if (n.IsNull()) return {};
        if (!n.IsSequence()) d.fail(key, "expected a list of words like [a, b], got " + shortText(n));
        std::vector<std::string> out;
        for (const auto& item : n) {
            if (!item.IsScalar()) d.fail(key, "expected a list of words, got " + shortText(n));
            out.push_back(item.Scalar());
        }
        return out;
    }
};

template <> struct DictConvert<Vec3> {
    static Vec3 from(const Dict& d, const std::string& key, const YAML::Node& n) {
        if (!n.IsSequence() || n.size() != 3)
            d.fail(key, "expected a vector of 3 numbers like [0, 0, 1], got " + shortText(n));
        Vec3 v;
        for (int i = 0; i < 3; ++i)
            if (!parseDouble(n[i], v[i]) || !inRange(v[i]))
                d.fail(key, "expected a vector of 3 finite numbers" + rangeText + ", got " + shortText(n));
        return v;
    }
};

template <> struct DictConvert<Quat> {
    static Quat from(const Dict& d, const std::string& key, const YAML::Node& n) {
        if (!n.IsSequence() || n.size() != 4)
            d.fail(key, "expected a quaternion [w, x, y, z], got " + shortText(n));
        double c[4];
        for (int i = 0; i < 4; ++i)
            if (!parseDouble(n[i], c[i]) || !inRange(c[i]))
                d.fail(key, "expected a quaternion of 4 finite numbers" + rangeText + ", got " + shortText(n));
        Quat q(c[0], c[1], c[2], c[3]);
        if (q.coeffs().stableNorm() < 1e-12) d.fail(key, "quaternion has zero length");
        return q.normalized();
    }
};

// The type and default as -doc prints them (KeyRecord).
template <class T> struct DocText;
template <> struct DocText<double> {
    static constexpr const char* type = "number";
    static std::string text(double x) {
        std::ostringstream os;
        os << x;
        return os.str();
    }
};
template <> struct DocText<int> {
    static constexpr const char* type = "integer";
    static std::string text(int x) { return std::to_string(x); }
};
template <> struct DocText<bool> {
    static constexpr const char* type = "true/false";
    static std::string text(bool x) { return x ? "true" : "false"; }
};
template <> struct DocText<std::string> {
    static constexpr const char* type = "word";
    static std::string text(const std::string& x) { return x.empty() ? "\"\"" : x; }
};
template <class V> std::string listText(const V& v) {
    std::string out = "[";
    for (std::size_t i = 0; i < static_cast<std::size_t>(v.size()); ++i)
        out += (i ? ", " : "") + DocText<std::decay_t<decltype(v[0])>>::text(v[i]);
    return out + "]";
}
template <> struct DocText<Vec3> {
    static constexpr const char* type = "vector [x, y, z]";
    static std::string text(const Vec3& x) { return listText(std::vector<double>{x.x(), x.y(), x.z()}); }
};
template <> struct DocText<Quat> {
    static constexpr const char* type = "quaternion [w, x, y, z]";
    static std::string text(const Quat& q) { return listText(std::vector<double>{q.w(), q.x(), q.y(), q.z()}); }
};
template <> struct DocText<std::vector<double>> {
    static constexpr const char* type = "list of numbers";
    static std::string text(const std::vector<double>& x) { return listText(x); }
};
template <> struct DocText<std::vector<std::vector<double>>> {
    static constexpr const char* type = "list of rows of numbers";
    static std::string text(const std::vector<std::vector<double>>& x) {
        std::string out = "[";
        for (std::size_t i = 0; i < x.size(); ++i) out += (i ? ", " : "") + listText(x[i]);
        return out + "]";
    }
};
template <> struct DocText<std::vector<std::string>> {
    static constexpr const char* type = "list of words";
    static std::string text(const std::vector<std::string>& x) { return listText(x); }
};

template <class T> T Dict::get(const std::string& key) const {
    T out = DictConvert<T>::from(*this, key, required(key));
    if (KeyRecord* r = record(key)) r->type = DocText<T>::type, r->required = true;
    return out;
}

template <class T> T Dict::get(const std::string& key, const T& fallback) const {
    if (KeyRecord* r = record(key)) r->type = DocText<T>::type, r->fallback = DocText<T>::text(fallback);
    YAML::Node v = value(key);
    if (!v.IsDefined()) return fallback;
    return DictConvert<T>::from(*this, key, v);
}

template double Dict::get<double>(const std::string&) const;
template int Dict::get<int>(const std::string&) const;
template bool Dict::get<bool>(const std::string&) const;
template std::string Dict::get<std::string>(const std::string&) const;
template Vec3 Dict::get<Vec3>(const std::string&) const;
template Quat Dict::get<Quat>(const std::string&) const;
template std::vector<double> Dict::get<std::vector<double>>(const std::string&) const;
template std::vector<std::string> Dict::get<std::vector<std::string>>(const std::string&) const;
template std::vector<std::vector<double>> Dict::get<std::vector<std::vector<double>>>(const std::string&) const;
template std::vector<std::vector<double>> Dict::get<std::vector<std::vector<double>>>(
    const std::string&, const std::vector<std::vector<double>>&) const;
template double Dict::get<double>(const std::string&, const double&) const;
template int Dict::get<int>(const std::string&, const int&) const;
template bool Dict::get<bool>(const std::string&, const bool&) const;
template std::string Dict::get<std::string>(const std::string&, const std::string&) const;
template Vec3 Dict::get<Vec3>(const std::string&, const Vec3&) const;
template Quat Dict::get<Quat>(const std::string&, const Quat&) const;
template std::vector<double> Dict::get<std::vector<double>>(const std::string&, const std::vector<double>&) const;
template std::vector<std::string> Dict::get<std::vector<std::string>>(const std::string&,
                                                                      const std::vector<std::string>&) const;

} // namespace mag
