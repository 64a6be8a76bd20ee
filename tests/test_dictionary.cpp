// Dict: typed reads, defaults, and the error messages users see for bad input.
#include <magFoam/Dictionary.hpp>
#include <magFoam/Error.hpp>

#include <catch2/catch.hpp>

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
