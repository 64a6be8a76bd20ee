// Dict: typed reads, defaults, and the error messages users see for bad input.
#include <magFoam/Dictionary.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/InputFile.hpp>

#include "expectError.hpp"

#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>

using mag::Dict;
using mag::InputError;
using Catch::Matchers::Contains;

TEST_CASE("typed reads and defaults", "[dictionary]") {
    const Dict d = Dict::fromString("a: 1.5\nn: 3\nflag: yes\nword: MBM\nv: [1, 2, 3]\n"
                                    "q: [1, 0, 0, 0]\nlist: [x, y]\nsub: {k: 2}\n",
                                    "test.yaml");
    CHECK(d.get<double>("a") == 1.5);
    CHECK(d.get<int>("n") == 3);
    CHECK(d.get<bool>("flag"));
    CHECK(d.get<std::string>("word") == "MBM");
    CHECK(d.get<mag::Vec3>("v") == mag::Vec3(1, 2, 3));
    CHECK(d.get<mag::Quat>("q").w() == 1.0);
    CHECK(d.get<std::vector<std::string>>("list").size() == 2);
    CHECK(d.sub("sub").get<int>("k") == 2);
    CHECK(d.get<double>("missing", 7.0) == 7.0);
    CHECK_NOTHROW(d.reportUnused());
}

TEST_CASE("malformed YAML names file, line and column", "[dictionary][badInput]") {
    CHECK_THROWS_WITH(Dict::fromString("a: [1, 2\nb: 3\n", "system/controlDict.yaml"),
                      Contains("system/controlDict.yaml:") && Contains("malformed YAML"));
    CHECK_THROWS_WITH(Dict::fromString("- 1\n- 2\n", "x.yaml"), Contains("x.yaml:1:1") && Contains("mapping"));
}

TEST_CASE("wrong type for a key", "[dictionary][badInput]") {
    const Dict d = Dict::fromString("deltaT: fast\npos: [1, 2]\nn: 2.5\nok: maybe\n", "c.yaml");
    CHECK_THROWS_WITH(d.get<double>("deltaT"), Contains("c.yaml:1:9") && Contains("deltaT") && Contains("number"));
    CHECK_THROWS_WITH(d.get<mag::Vec3>("pos"), Contains("c.yaml:2:6") && Contains("3 numbers"));
    CHECK_THROWS_WITH(d.get<int>("n"), Contains("integer"));
    CHECK_THROWS_WITH(d.get<bool>("ok"), Contains("true or false"));
    CHECK_THROWS_WITH(d.get<double>("absent"), Contains("absent") && Contains("required"));
}

TEST_CASE("NaN and inf are rejected with the key", "[dictionary][badInput]") {
    const Dict d = Dict::fromString("position: [0, .nan, 0]\nx: .inf\ny: nan\n", "constant/bodies.yaml");
    CHECK_THROWS_WITH(d.get<mag::Vec3>("position"), Contains("constant/bodies.yaml:1:11") && Contains("position") &&
                                                         Contains("finite"));
    CHECK_THROWS_WITH(d.get<double>("x"), Contains("finite"));
    CHECK_THROWS_WITH(d.get<double>("y"), Contains("finite"));
}

TEST_CASE("unknown key: position, suggestion and valid keys", "[dictionary][badInput]") {
    const Dict d = Dict::fromString("deltaT: 0.1\ndeltaTT: 0.2\n", "system/controlDict.yaml");
    (void)d.get<double>("deltaT");
    (void)d.get<double>("endTime", 1.0);
    CHECK_THROWS_WITH(d.reportUnused(), Contains("system/controlDict.yaml:2:1") && Contains("unknown key 'deltaTT'") &&
                                            Contains("did you mean 'deltaT'") && Contains("endTime"));
}

TEST_CASE("a missing required key names a misspelt one beside it", "[dictionary][badInput]") {
    const Dict d = Dict::fromString("name: a\nmagnetisation: [0, 0, 1]\n", "constant/bodies.yaml");
    (void)d.get<std::string>("name");
    CHECK_THROWS_WITH(d.get<mag::Vec3>("magnetization"),
                      Contains("magnetization: required key is missing") && Contains("constant/bodies.yaml:2:1") &&
                          Contains("unknown key 'magnetisation': did you mean 'magnetization'?"));
    // Nothing alike: the plain message.
    CHECK_THROWS_WITH(d.get<double>("density"), Contains("required key is missing") && !Contains("did you mean"));
}

TEST_CASE("nested key paths and duplicate keys", "[dictionary][badInput]") {
    const Dict d = Dict::fromString("bodies:\n  - name: a\n    geometry: {box: {size: [1, x, 1]}}\n", "b.yaml");
    const auto bodies = d.list("bodies");
    const Dict box = bodies[0].sub("geometry").sub("box");
    CHECK_THROWS_WITH(box.get<mag::Vec3>("size"), Contains("bodies[0].geometry.box.size"));
    CHECK_THROWS_WITH(Dict::fromString("a: 1\na: 2\n", "d.yaml"), Contains("d.yaml:2:1") && Contains("duplicate"));
}

TEST_CASE("enumerated words list the valid values", "[dictionary][badInput]") {
    const Dict d = Dict::fromString("startFrom: lastTime\n", "c.yaml");
    CHECK_THROWS_WITH(d.getWord("startFrom", {"startTime", "latestTime"}),
                      Contains("lastTime") && Contains("startTime, latestTime"));
}

TEST_CASE("missing dictionary file", "[dictionary][badInput]") {
    CHECK_THROWS_WITH(Dict::fromFile("no/such/dir/controlDict.yaml"),
                      Contains("no/such/dir/controlDict.yaml") && Contains("not found"));
}

// ---------------------------------------------------------------------------
// What the reader refuses before anything walks the tree (tests/badDictionaries).

namespace {

std::filesystem::path badDictionary(const std::string& name) {
    return std::filesystem::path(MAG_SOURCE_DIR) / "tests/badDictionaries" / name;
}

using magtest::inputErrorOf;

// A scratch folder for files that cannot live in the repository (FIFO, links).
struct ScratchDir {
    std::filesystem::path path;
    ScratchDir() {
        path = std::filesystem::temp_directory_path() /
               ("magFoam-dict-" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
        std::filesystem::create_directories(path);
    }
    ~ScratchDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
};

} // namespace

TEST_CASE("an alias bomb is refused quickly, also inside an unknown key", "[dictionary][badInput]") {
    for (const std::string name : {"aliasBomb.yaml", "aliasBombInUnknownKey.yaml"}) {
        INFO(name);
        const auto start = std::chrono::steady_clock::now();
        const std::string message = inputErrorOf([&] { (void)Dict::fromFile(badDictionary(name)); });
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        CHECK_THAT(message, Contains(name + ":") && Contains("expands to more than 1000000 values"));
        CHECK(seconds < 2.0);
    }
    // An alias inside its own anchor would be an endless tree.
    CHECK_THAT(inputErrorOf([&] { (void)Dict::fromFile(badDictionary("aliasCycle.yaml")); }),
               Contains("aliasCycle.yaml:1:") && Contains("alias *a refers to a node that contains it"));
    // Aliases as such are fine, and count as what they stand for.
    const Dict d = Dict::fromString("base: &b [1, 2, 3]\ncopy: *b\n", "ok.yaml");
    CHECK(d.get<std::vector<double>>("copy").size() == 3);
}

TEST_CASE("nesting deeper than the parser's limit is an error, not a stack overflow", "[dictionary][badInput]") {
    CHECK_THAT(inputErrorOf([&] { (void)Dict::fromFile(badDictionary("deepNesting.yaml")); }),
               Contains("deepNesting.yaml:") && Contains("nested more than 499 levels deep"));
}

TEST_CASE("a second YAML document is an error naming its line", "[dictionary][badInput]") {
    CHECK_THAT(inputErrorOf([&] { (void)Dict::fromFile(badDictionary("twoDocuments.yaml")); }),
               Contains("twoDocuments.yaml:2:") && Contains("a second YAML document"));
    // A document end marker alone is one document.
    CHECK_NOTHROW(Dict::fromString("---\na: 1\n...\n", "one.yaml"));
}

TEST_CASE("numbers above 1e30 in magnitude are refused, naming the key", "[dictionary][badInput]") {
    const Dict d = Dict::fromFile(badDictionary("hugeNumber.yaml"));
    CHECK_THROWS_WITH(d.get<double>("Br"), Contains("hugeNumber.yaml:1:") && Contains("Br: expected a finite number "
                                                                                      "of magnitude at most 1e30"));
    CHECK_THROWS_WITH(d.get<mag::Vec3>("position"), Contains("hugeNumber.yaml:2:") && Contains("position"));
    CHECK_THROWS_WITH((d.get<std::vector<std::vector<double>>>("rows")), Contains("rows") && Contains("1e30"));
    CHECK_THROWS_WITH(d.get<mag::Quat>("q"), Contains("q: expected a quaternion") && Contains("1e30"));
    CHECK(Dict::fromString("x: -1e30\n", "ok.yaml").get<double>("x") == -1e30);
}

TEST_CASE("non-regular files, dangling links and files above the size limit are refused", "[dictionary][badInput]") {
    namespace fs = std::filesystem;
    const ScratchDir dir;
    const fs::path fifo = dir.path / "controlDict.yaml";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    // Returns at once (a FIFO would block a reader forever), naming the file.
    CHECK_THAT(inputErrorOf([&] { (void)Dict::fromFile(fifo); }),
               Contains(fifo.string() + ": is a FIFO (named pipe), expected a regular dictionary"));

    const fs::path zero = dir.path / "bodies.yaml";
    fs::create_symlink("/dev/zero", zero);
    CHECK_THAT(inputErrorOf([&] { (void)Dict::fromFile(zero); }),
               Contains(zero.string() + ": is a character device, expected a regular dictionary"));

    const fs::path dangling = dir.path / "forcesDict.yaml";
    fs::create_symlink(dir.path / "missing.yaml", dangling);
    CHECK_THAT(inputErrorOf([&] { (void)Dict::fromFile(dangling); }),
               Contains(dangling.string() + ": file not found (a link to a missing file)"));
    CHECK(mag::inputPresent(dangling));
    CHECK_FALSE(mag::inputPresent(dir.path / "missing.yaml"));

    const fs::path big = dir.path / "materials.yaml";
    { std::ofstream(big) << "a: 1\n"; }
    fs::resize_file(big, mag::dictionaryFileLimit + 1);  // sparse: no disk used
    CHECK_THAT(inputErrorOf([&] { (void)Dict::fromFile(big); }),
               Contains(big.string() + ": dictionary of 67108865 bytes is above the limit of 67108864 bytes"));

    CHECK_THAT(inputErrorOf([&] { (void)Dict::fromFile(dir.path / "none.yaml"); }), Contains("none.yaml: file not found"));
}
