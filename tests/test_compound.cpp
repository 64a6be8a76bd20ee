// Compound bodies (Parts.hpp, docs/compound-bodies.md): one rigid body made of
// parts. Forces against the Akoun-Yonnet closed form summed over the parts,
// Newton's third law and the angular momentum balance, mass properties against
// the analytic values, soft parts magnetized by their own body, a compound
// resting on the ground like the single body of its shape, and bad input.
#include "bodyFixture.hpp"
#include "caseFixture.hpp"
#include "expectError.hpp"
#include "oracles/akounYonnet.hpp"

#include <magFoam/Case.hpp>
#include <magFoam/Dictionary.hpp>
#include <magFoam/InductionModel.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/MeshPrimitives.hpp>
#include <magFoam/Parts.hpp>
#include <magFoam/ResultsWriter.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using mag::Vec3;
using magtest::axisAngle;
using magtest::boxShape;

namespace {

const Vec3 cube = Vec3::Constant(0.01);

mag::Material material(const std::string& name, double density, double Br, bool soft = false) {
    mag::Material m;
    m.name = name;
    m.density = density;
    m.Br = Br;
    m.model = soft ? mag::Material::Model::soft : mag::Material::Model::permanent;
    if (soft) m.properties = {{"chi", 1000.0}, {"Js", 2.0}};
    return m;
}

const mag::Material N42 = material("N42", 7500, 1.3);

mag::Part part(std::shared_ptr<const mag::Shape> shape, const mag::Material& m, const Vec3& position,
               const mag::Quat& orientation = mag::Quat::Identity()) {
    return mag::Part{std::move(shape), m, position, orientation};
}

// A compound of `parts` (placed in their layout) with the given part
// magnetizations (A/m, part frames), its centre of mass at `position`.
mag::Body compound(const std::string& name, std::vector<mag::Part> parts, std::vector<Vec3> magnetization,
                   const Vec3& position, const mag::Quat& orientation = mag::Quat::Identity()) {
    const mag::CompoundLayout layout = mag::makeCompound(std::move(parts));
    mag::Body b;
    b.name = name;
    b.shape = layout.shape;
    b.compound = layout.compound;
    b.partMagnetization = std::move(magnetization);
    b.magnetizationBody = mag::meanMagnetization(*b.compound, b.partMagnetization);
    b.position = position;
    b.orientation = orientation;
    return b;
}

mag::Body cubeMagnet(const std::string& name, const Vec3& position, double Br) {
    mag::Body b = magtest::magnet(name, boxShape(cube), position, Vec3::UnitZ());
    b.material = N42;
    b.magnetizationBody = Vec3(0, 0, Br / mag::mu0);
    return b;
}

mag::MagneticSystem magnetsOf(const std::string& field, const std::string& induction = "type: none") {
    return mag::MagneticSystem(magtest::field(field), mag::InductionModel::New(mag::Dict::fromString(induction, "test")));
}

double relative(const Vec3& a, const Vec3& b) { return (a - b).norm() / b.norm(); }

} // namespace

TEST_CASE("compound: the force on a cube is the sum of the Akoun-Yonnet forces of the parts, Newton's third law",
          "[compound]") {
    // Two 1 cm cubes magnetized +z and -z, 1 mm apart along x; a third cube
    // (+z) 2 mm above them, off the axis of symmetry.
    const double J = 1.3;
    const Vec3 left(-0.0055, 0, 0), right(0.0055, 0, 0), probeAt(0.003, 0.002, 0.012);
    mag::Body pair = compound("pair", {part(boxShape(cube), N42, left), part(boxShape(cube), N42, right)},
                              {Vec3(0, 0, J / mag::mu0), Vec3(0, 0, -J / mag::mu0)}, Vec3::Zero());
    CHECK(pair.position == Vec3::Zero());
    const std::vector<mag::Body> bodies = {pair, cubeMagnet("probe", probeAt, J)};
    const Vec3 expected = oracle::akounYonnetForce(cube, left, cube, probeAt, J, J) +
                          oracle::akounYonnetForce(cube, right, cube, probeAt, -J, J);

    // The closed form is the charge model's force; MBM's quadrature of it is
    // converged to 1e-6 with 20 x 20 Gauss points per face at a 2 mm gap
    // (and to 1e-7 by the adaptive rule at tolerance 1e-8).
    for (const auto& [field, tol] : std::vector<std::pair<std::string, double>>{
             {"type: MBM\nquadrature: {type: gauss, n: 20}", 1e-6},
             {"type: MBM\nquadrature: {type: adaptive, tolerance: 1e-8}", 1e-7}}) {
        INFO(field);
        const mag::MagneticSystem magnets = magnetsOf(field);
        const std::vector<mag::Wrench> w = magnets.wrenches(bodies);
        CHECK(relative(w[1].force, expected) < tol);
        // Newton's third law: the compound feels the opposite force, and the
        // torques balance about any point (here the compound's centre).
        CHECK((w[0].force + w[1].force).norm() < 1e-12 * expected.norm());
        const Vec3 L = w[0].totalTorque() + w[1].totalTorque() + (probeAt - pair.position).cross(w[1].force);
        CHECK(L.norm() < 1e-12 * expected.norm() * 0.01);

        // The compound's torque about its centre of mass is the parts' wrenches
        // (each evaluated on its own, sampled on the part) moved there.
        Vec3 moved = Vec3::Zero();
        for (std::size_t k = 0; k < 2; ++k) {
            const mag::Body p = mag::PartBodies::part(pair, k, 0);
            const mag::Wrench pw = magnets.fieldEvaluator().interaction(bodies[1], p);
            moved += pw.totalTorque() + (p.position - pair.position).cross(pw.force);
        }
        CHECK(relative(w[0].totalTorque(), moved) < 10 * tol);
    }
}

TEST_CASE("compound: a turned, moved compound acts as its parts placed one by one", "[compound]") {
    // A Halbach-like row of three cubes (+z, +x, -z), turned and moved: its
    // parts as separate fixed bodies exert the same wrench on a probe cube.
    const double J = 1.3;
    const mag::Quat q = axisAngle(35, Vec3(1, 2, 0.5));
    mag::Body row = compound("row",
                             {part(boxShape(cube), N42, Vec3(-0.01, 0, 0)), part(boxShape(cube), N42, Vec3::Zero()),
                              part(boxShape(cube), N42, Vec3(0.01, 0, 0), axisAngle(90, Vec3::UnitY()))},
                             {Vec3(0, 0, J / mag::mu0), Vec3(J / mag::mu0, 0, 0), Vec3(-J / mag::mu0, 0, 0)},
                             Vec3(0.001, -0.002, 0.003), q);
    // The third part is turned by 90 deg about y, which takes its -x to the
    // body's +z: in the body frame the row reads +z, +x, +z.
    CHECK(relative(row.magnetizationBody, Vec3(J / mag::mu0, 0, 2 * J / mag::mu0) / 3) < 1e-14);
    const mag::Body probe = cubeMagnet("probe", Vec3(0.004, 0.003, 0.02), J);
    std::vector<mag::Body> separate;
    for (std::size_t k = 0; k < 3; ++k) separate.push_back(mag::PartBodies::part(row, k, 0));
    separate.push_back(probe);
    const mag::MagneticSystem magnets = magnetsOf("type: MBM\nquadrature: {type: gauss, n: 8}");
    const std::vector<mag::Wrench> w = magnets.wrenches({row, probe});
    const std::vector<mag::Wrench> s = magnets.wrenches(separate);
    // The same pairs in the same orientation: equal to rounding.
    CHECK(relative(w[1].force, s[3].force) < 1e-13);
    CHECK(relative(w[1].totalTorque(), s[3].totalTorque()) < 1e-13);
    Vec3 F = Vec3::Zero(), T = Vec3::Zero();
    for (std::size_t k = 0; k < 3; ++k)
        F += s[k].force, T += s[k].totalTorque() + (separate[k].position - row.position).cross(s[k].force);
    CHECK(relative(w[0].force, F) < 1e-13);
    CHECK(relative(w[0].totalTorque(), T) < 1e-12);
    // The field of the compound is its parts'.
    const std::vector<Vec3> points = {Vec3(0.0, 0.0, 0.012), Vec3(-0.02, 0.01, 0.0), Vec3(0.001, -0.002, 0.003)};
    std::vector<Vec3> Bc(3), Bs(3);
    magnets.field({row}, points, Bc);
    separate.pop_back();
    magnets.field(separate, points, Bs);
    for (std::size_t i = 0; i < 3; ++i) CHECK((Bc[i] - Bs[i]).norm() < 1e-14 * Bs[i].norm() + 1e-18);
    // Excluding the compound excludes all its parts.
    std::vector<Vec3> Bx(3);
    const std::vector<mag::Body> both = {row, probe};
    magnets.field(both, points, Bx, {}, {}, &both[0]);
    std::vector<Vec3> Bp(3);
    magnets.field({probe}, points, Bp);
    for (std::size_t i = 0; i < 3; ++i) CHECK((Bx[i] - Bp[i]).norm() <= 1e-15 * Bp[i].norm());
}

TEST_CASE("compound: pairs within a compound exert nothing, and are not evaluated", "[compound]") {
    // Two touching cubes that repel strongly: as one compound, zero wrench.
    const double J = 1.3;
    mag::Body pair = compound("pair", {part(boxShape(cube), N42, Vec3(0, 0, -0.005)), part(boxShape(cube), N42, Vec3(0, 0, 0.005))},
                              {Vec3(0, 0, J / mag::mu0), Vec3(0, 0, -J / mag::mu0)}, Vec3::Zero());
    for (const char* field : {"type: MBM", "type: EDM\nn: 3", "type: hybrid"}) {
        INFO(field);
        const mag::MagneticSystem magnets = magnetsOf(field);
        const std::vector<mag::Wrench> w = magnets.wrenches({pair});
        CHECK(w[0].force == Vec3::Zero());
        CHECK(w[0].totalTorque() == Vec3::Zero());
    }
}

TEST_CASE("compound: mass, centre of mass and inertia of a box and a cylinder", "[compound]") {
    const Vec3 size(0.02, 0.01, 0.006);
    const double rhoBox = 7500, rhoCyl = 2700, r = 0.004, h = 0.012;
    const Vec3 pBox(0.001, 0.002, -0.003), pCyl(0.013, -0.004, 0.002);
    const mag::Quat qCyl = axisAngle(90, Vec3::UnitX());  // the cylinder's axis along -y
    const mag::Material steel = material("box", rhoBox, 1.0), alu = material("cyl", rhoCyl, 1.0);

    // Box alone: exact (rounding only), its layout's centre moved to the origin.
    {
        const mag::CompoundLayout c = mag::makeCompound({part(boxShape(size), steel, pBox)});
        const double m = rhoBox * size.prod();
        CHECK(std::abs(c.compound->mass - m) < 1e-12 * m);
        CHECK((c.centreOfMass - pBox).norm() < 1e-15);
        const Vec3 I = m / 12 * Vec3(size.y() * size.y() + size.z() * size.z(), size.x() * size.x() + size.z() * size.z(),
                                     size.x() * size.x() + size.y() * size.y());
        CHECK((c.compound->inertia - mag::Mat3(I.asDiagonal())).norm() < 1e-12 * I.norm());
    }

    // Box and cylinder: the analytic compound (parallel axes), approached as the
    // cylinder's polygon gets more segments (error ~ 1/segments^2).
    const double mBox = rhoBox * size.prod(), mCyl = rhoCyl * mag::pi * r * r * h, M = mBox + mCyl;
    const Vec3 C = (mBox * pBox + mCyl * pCyl) / M;
    auto shifted = [](double m, const Vec3& d) { return mag::Mat3(m * (d.squaredNorm() * mag::Mat3::Identity() - d * d.transpose())); };
    const mag::Mat3 Ibox = mag::Mat3(Vec3(mBox / 12 * (size.y() * size.y() + size.z() * size.z()),
                                          mBox / 12 * (size.x() * size.x() + size.z() * size.z()),
                                          mBox / 12 * (size.x() * size.x() + size.y() * size.y()))
                                         .asDiagonal());
    const double across = mCyl * (3 * r * r + h * h) / 12, along = mCyl * r * r / 2;
    const mag::Mat3 R = qCyl.toRotationMatrix();
    const mag::Mat3 Icyl = R * mag::Mat3(Vec3(across, across, along).asDiagonal()) * R.transpose();
    const mag::Mat3 I = Ibox + shifted(mBox, pBox - C) + Icyl + shifted(mCyl, pCyl - C);

    double lastError = 1;
    for (int segments : {32, 64, 128, 256}) {
        INFO("segments " << segments);
        mag::ShapeKind kind;
        kind.kind = mag::ShapeKind::Kind::cylinder;
        const auto cyl = mag::makeShape(mag::makeCylinder(r, h, segments), kind);
        const mag::CompoundLayout c = mag::makeCompound({part(boxShape(size), steel, pBox), part(cyl, alu, pCyl, qCyl)});
        const double error = std::max({std::abs(c.compound->mass - M) / M, (c.centreOfMass - C).norm() / h,
                                       (c.compound->inertia - I).norm() / I.norm()});
        CHECK(error < 0.3 * lastError);  // ~ 1/4 per doubling
        lastError = error;
        // The parts sit about the centre of mass.
        CHECK((c.compound->parts[0].position - (pBox - c.centreOfMass)).norm() < 1e-15);
    }
    CHECK(lastError < 2e-4);
}

TEST_CASE("compound: a soft part is magnetized by the other parts of its body", "[compound]") {
    // A magnet with a steel cube on top, as one compound and as two bodies: the
    // steel's magnetization and the force on a probe magnet are the same.
    const mag::Material steel = material("steel", 7850, 0, true);
    const double J = 1.3;
    const Vec3 probeAt(0.003, 0, 0.03);
    const std::string field = "type: MBM\nquadrature: {type: gauss, n: 6}";
    const std::string demag = "type: demag\ntolerance: 1e-12";
    mag::Body holder = compound("holder",
                                {part(boxShape(cube), N42, Vec3::Zero()), part(boxShape(Vec3(0.01, 0.01, 0.004)), steel, Vec3(0, 0, 0.0071))},
                                {Vec3(0, 0, J / mag::mu0), Vec3::Zero()}, Vec3::Zero());
    std::vector<mag::Body> one = {holder, cubeMagnet("probe", probeAt, J)};
    std::vector<mag::Body> two = {mag::PartBodies::part(holder, 0, 0), mag::PartBodies::part(holder, 1, 0), one[1]};
    two[1].fixed = two[0].fixed = true;
    one[0].fixed = true;
    const mag::MagneticSystem a = magnetsOf(field, demag), b = magnetsOf(field, demag);
    a.converge(one);
    b.converge(two);
    CHECK(one[0].partMagnetization[1].norm() > 1e5);  // magnetized by its own magnet
    CHECK(relative(one[0].partMagnetization[1], two[1].magnetizationBody) < 1e-12);
    const std::vector<mag::Wrench> wa = a.wrenches(one), wb = b.wrenches(two);
    CHECK(relative(wa[1].force, wb[2].force) < 1e-12);
    // The scene energy counts the pair within the compound once its part is soft.
    CHECK(std::abs(a.magneticEnergy(one, wa) - b.magneticEnergy(two, b.wrenches(two))) <
          1e-10 * std::abs(b.magneticEnergy(two, b.wrenches(two))));
}

TEST_CASE("compound: a held body's parts are held, and keep their pairs' orientation", "[compound][sleeping]") {
    // A sleeping body is fixed and held in the solver's view (Body::held,
    // docs/dynamics.md#sleeping); its parts must be too, or their pairs with
    // moving bodies turn round and the wrench changes with the rule's error.
    const std::string field = "type: MBM\nquadrature: {type: regular, n: 1}";
    mag::Body holder = compound("holder",
                                {part(boxShape(cube), N42, Vec3::Zero()), part(boxShape(cube), N42, Vec3(0.01, 0, 0))},
                                {Vec3(0, 0, 1.3 / mag::mu0), Vec3(0, 0, 1.3 / mag::mu0)}, Vec3::Zero());
    const std::vector<mag::Body> moving = {holder, cubeMagnet("probe", Vec3(0.004, 0.002, 0.0105), 1.3)};
    std::vector<mag::Body> held = moving;
    held[0].fixed = held[0].held = true;
    const mag::PartBodies view(held);
    for (const mag::Body& p : view.parts)
        if (p.name.starts_with("holder/")) CHECK(p.held);
    const mag::MagneticSystem m = magnetsOf(field, "type: none");
    const std::vector<mag::Wrench> a = m.wrenches(moving), b = m.wrenches(held, true);
    CHECK(b[1].force == a[1].force);
    CHECK(b[1].totalTorque() == a[1].totalTorque());
}

namespace {

void writeDropCase(magtest::TempCase& c, const std::string& body, double endTime = 0.25) {
    c.write("system/controlDict.yaml", "deltaT: 0.0005\nendTime: " + std::to_string(endTime) + "\nwriteInterval: 0.05\n");
    c.write("system/magSchemes.yaml", "field: {type: MBM}\n");
    c.write("constant/materials.yaml", "N42: {model: permanent, Br: 1.3, density: 7500}\n"
                                       "plastic: {model: permanent, Br: 0, density: 1200}\n");
    c.write("constant/rigidBody.yaml", "type: ODE\ngravity: [0, 0, -9.81]\nground: {height: 0}\n"
                                       "contact: {friction: 0.5, restitution: 0.1}\n");
    c.write("constant/bodies.yaml", "bodies:\n" + body);
}

struct EndState {
    Vec3 position, velocity;
    mag::Quat orientation;
};

EndState endState(const std::filesystem::path& dir) {
    const auto folder = mag::latestTimeFolder(dir);
    REQUIRE(folder.has_value());
    const mag::Dict d = mag::Dict::fromFile(*folder / "bodies.yaml");
    const mag::Dict b = d.list("bodies").at(0);
    return {b.get<Vec3>("position"), b.get<Vec3>("velocity"), b.get<mag::Quat>("orientation")};
}

} // namespace

TEST_CASE("compound: falls and rests on the ground like a single body of its shape (ODE)", "[compound][app]") {
    // A 20 x 10 x 6 mm bar, tilted, dropped from 8 mm: as one box, and as a
    // magnet and a plastic block of the same size side by side (different
    // densities, so the centre of mass is off the middle).
    const std::string tilt = "orientation: {axis: [1, 1, 0], angle: 10}";
    magtest::TempCase single, parts;
    writeDropCase(single, "  - {name: bar, geometry: {box: {size: [0.02, 0.01, 0.006]}}, material: N42,\n"
                          "     magnetization: [0, 0, 1], position: [0, 0, 0.008], " + tilt + "}\n");
    writeDropCase(parts, "  - name: bar\n"
                         "    parts:\n"
                         "      - {geometry: {box: {size: [0.01, 0.01, 0.006]}}, material: N42, magnetization: [0, 0, 1],\n"
                         "         position: [-0.005, 0, 0]}\n"
                         "      - {geometry: {box: {size: [0.01, 0.01, 0.006]}}, material: plastic, magnetization: [0, 0, 1],\n"
                         "         position: [0.005, 0, 0]}\n"
                         "    position: [0, 0, 0.008]\n    orientation: {axis: [1, 1, 0], angle: 10}\n");
    REQUIRE(magtest::runApp(single.dir(), "magFoam", "log") == 0);
    REQUIRE(magtest::runApp(parts.dir(), "magFoam", "log") == 0);
    const EndState a = endState(single.dir()), b = endState(parts.dir());
    // Both lie flat on the ground: centre at half the height, at rest.
    CHECK(a.position.z() == Approx(0.003).margin(2e-5));
    CHECK(b.position.z() == Approx(0.003).margin(2e-5));
    CHECK(a.velocity.norm() < 1e-3);
    CHECK(b.velocity.norm() < 1e-3);
    const Vec3 upA = a.orientation * Vec3::UnitZ(), upB = b.orientation * Vec3::UnitZ();
    CHECK(upA.z() > 1 - 1e-6);
    CHECK(upB.z() > 1 - 1e-6);
    // Outputs: one bodies.csv row per body per write; VTK faces carry the part.
    const std::string csv = magtest::slurp(parts.path("postProcessing/bodies.csv"));
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 1 + 6);
    const std::string vtp = magtest::slurp(parts.path("VTK/bodies_0.vtp"));
    CHECK_THAT(vtp, Catch::Matchers::Contains("Name=\"part\""));
    CHECK_THAT(magtest::slurp(parts.path("0.05/bodies.yaml")), Catch::Matchers::Contains("partMagnetization"));
    CHECK_THAT(magtest::slurp(parts.path("log")), Catch::Matchers::Contains("centre of mass at"));
    // magCheckMesh checks every part's mesh.
    REQUIRE(magtest::runApp(parts.dir(), "magCheckMesh", "log.check") == 0);
    const std::string check = magtest::slurp(parts.path("log.check"));
    CHECK_THAT(check, Catch::Matchers::Contains(" part 1 ("));
    CHECK_THAT(check, Catch::Matchers::Contains("all 2 meshes OK"));
}

TEST_CASE("compound: bad input names the file, the body and the part", "[compound][input]") {
    auto errorOf = [](const std::string& bodies) {
        magtest::TempCase c;
        writeDropCase(c, bodies);
        return magtest::inputErrorOf([&] { (void)mag::Case::read(c.dir()); });
    };
    const std::string good = "{geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N42, magnetization: [0, 0, 1]}";

    std::string e = errorOf("  - {name: h, position: [0, 0, 0.01], parts: [" + good + ", {material: N42, magnetization: [0, 0, 1]}]}\n");
    CHECK(magtest::contains(e, "bodies.yaml"));
    CHECK(magtest::contains(e, "parts[1]"));
    CHECK(magtest::contains(e, "part 1 of body 'h' has no geometry"));

    magtest::TempCase soft;
    e = errorOf("  - {name: h, position: [0, 0, 0.01], parts: [" + good +
                ", {geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N42, position: [0.01, 0, 0]}]}\n");
    CHECK(magtest::contains(e, "parts[1].magnetization"));

    e = errorOf("  - {name: h, position: [0, 0, 0.01], geometry: {box: {size: [0.01, 0.01, 0.01]}}, parts: [" + good + "]}\n");
    CHECK(magtest::contains(e, "geometry"));
    CHECK(magtest::contains(e, "body 'h' has parts"));

    e = errorOf("  - {name: h, position: [0, 0, 0.01], parts: []}\n");
    CHECK(magtest::contains(e, "list of parts is empty"));

    e = errorOf("  - {name: h, position: [0, 0, 0.01], parts: [" + good + "], material: N42}\n");
    CHECK(magtest::contains(e, "give each part its own material"));

    // A magnetization on a soft part.
    {
        magtest::TempCase c;
        writeDropCase(c, "  - {name: h, position: [0, 0, 0.01], parts: [" + good +
                             ", {geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: steel, magnetization: [1, 0, 0],"
                             " position: [0.01, 0, 0]}]}\n");
        c.write("constant/materials.yaml", "N42: {model: permanent, Br: 1.3, density: 7500}\n"
                                           "steel: {model: soft, chi: 1000, Js: 2.0, density: 7850}\n");
        e = magtest::inputErrorOf([&] { (void)mag::Case::read(c.dir()); });
        CHECK(magtest::contains(e, "parts[1].magnetization"));
        CHECK(magtest::contains(e, "part 1 of body 'h': a soft material takes no magnetization"));
    }

    // Overlapping parts: a warning naming the body and both parts; the run goes on.
    magtest::TempCase overlap;
    writeDropCase(overlap, "  - {name: h, position: [0, 0, 0.01], parts: [" + good +
                               ", {geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N42, magnetization: [0, 0, 1],"
                               " position: [0.005, 0, 0]}]}\n",
                  0.001);
    REQUIRE(magtest::runApp(overlap.dir(), "magFoam", "log") == 0);
    const std::string log = magtest::slurp(overlap.path("log"));
    CHECK_THAT(log, Catch::Matchers::Contains("'h/0' and 'h/1' overlap"));
    CHECK_THAT(log, Catch::Matchers::Contains("(body 'h')"));
}

namespace {

// The force on a 10 mm steel cube (chi 1000, Js 2 T, demag) 1 mm above a fixed
// 10 mm N42 cube magnetized along x (its field changes sign across the
// steel), the steel split into `cells` per edge.
Vec3 steelCubeForce(int cells) {
    magtest::TempCase c;
    c.write("system/magSchemes.yaml", "field: {type: MBM, quadrature: {type: gauss, n: 4}}\ninduction: {type: demag}\n");
    c.write("constant/materials.yaml", "N42: {model: permanent, Br: 1.3, density: 7500}\n"
                                       "steel: {model: soft, chi: 1000, Js: 2.0, density: 7850}\n");
    c.write("constant/bodies.yaml",
            "bodies:\n"
            "  - {name: magnet, geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N42, magnetization: [1, 0, 0],\n"
            "     position: [0, 0, 0], motion: fixed}\n"
            "  - {name: steel, geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: steel, position: [0, 0, 0.011],\n"
            "     cells: " + std::to_string(cells) + "}\n");
    mag::Case cs = mag::Case::read(c.dir());
    const mag::MagneticSystem magnets(cs);
    std::vector<mag::Body> bodies = cs.bodies();
    REQUIRE(magnets.converge(bodies).converged);
    return magnets.wrenches(bodies)[1].force;
}

} // namespace

TEST_CASE("compound: cells let a soft cube's magnetization vary, its force converges", "[compound][demag]") {
    // One uniform magnetization sees the mean of a field that reverses across
    // the cube; cells (the method of moments) follow it. The force grows and
    // its steps shrink as the cells do.
    std::vector<double> Fz;
    for (int n : {1, 2, 3, 4}) {
        Fz.push_back(steelCubeForce(n).z());
        INFO("cells " << n << ": Fz " << Fz.back() << " N");
        CHECK(Fz.back() < 0);  // attracted
    }
    INFO("Fz for 1..4 cells per edge: " << Fz[0] << ", " << Fz[1] << ", " << Fz[2] << ", " << Fz[3] << " N");
    CHECK(std::abs(Fz[3] - Fz[2]) < std::abs(Fz[2] - Fz[1]));
    CHECK(std::abs(Fz[2] - Fz[1]) < std::abs(Fz[1] - Fz[0]));
    CHECK(std::abs(Fz[1]) > 2 * std::abs(Fz[0]));  // one cell misses most of it

    // Bad input: cells on a permanent magnet, on a sphere, out of range.
    magtest::TempCase c;
    writeDropCase(c, "  - {name: s, geometry: {sphere: {radius: 0.005}}, material: steel, position: [0, 0, 0.01], cells: 2}\n");
    c.write("constant/materials.yaml", "N42: {model: permanent, Br: 1.3, density: 7500}\n"
                                       "steel: {model: soft, chi: 1000, Js: 2.0, density: 7850}\n");
    std::string e = magtest::inputErrorOf([&] { (void)mag::Case::read(c.dir()); });
    CHECK(magtest::contains(e, "bodies[0].cells"));
    CHECK(magtest::contains(e, "cells split a box geometry"));
    writeDropCase(c, "  - {name: m, geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N42, magnetization: [0, 0, 1],"
                     " position: [0, 0, 0.01], cells: 2}\n");
    e = magtest::inputErrorOf([&] { (void)mag::Case::read(c.dir()); });
    CHECK(magtest::contains(e, "cells are for soft bodies"));
    writeDropCase(c, "  - {name: s, geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: steel, position: [0, 0, 0.01],"
                     " cells: [2, 2, 0.5]}\n");
    c.write("constant/materials.yaml", "N42: {model: permanent, Br: 1.3, density: 7500}\n"
                                       "steel: {model: soft, chi: 1000, Js: 2.0, density: 7850}\n");
    e = magtest::inputErrorOf([&] { (void)mag::Case::read(c.dir()); });
    CHECK(magtest::contains(e, "whole numbers 1..32"));
}
