// AppliedField: a field imposed from outside the bodies (a Helmholtz coil pair,
// a gradient coil, the Earth's field), selected by `type:` in
// constant/appliedField.yaml (none when the file is absent):
//
//   type: uniform                              B(r) = B
//   B: [0, 0, 0.01]                            # T
//
//   type: gradient                             B(r) = B + G (r - origin)
//   B: [0, 0, 0.01]                            # T at the origin
//   gradient: [[0, 0, 0], [0, 0, 0], [0, 0, 0]] # G_ij = dB_i/dx_j, T/m
//   origin: [0, 0, 0]                          # m
//
// G must be symmetric (curl B = 0: no currents where the bodies are) and
// traceless (div B = 0). Either may vary in time with `table:` rows
// [t, s] (B and G scaled by s) or [t, Bx, By, Bz] (B replaced, G kept),
// linear between rows, held beyond the first and last.
//
// It acts on every magnetized body (permanent and soft): the field's own
// wrench (exact for a uniformly magnetized body in a field linear in r:
// F = G m, torque m x B(c) about the centre of mass c, no mechanical torque,
// energy -m . B(c), m = M V), in the field of magField and at the soft bodies
// for the induction models. Coils (loops, polylines), whose fields are not
// linear, are a plugin of this registry that overrides wrench() with a
// boundary integral like MBM's.
#pragma once

#include "magFoam/Body.hpp"
#include "magFoam/Dictionary.hpp"
#include "magFoam/Registry.hpp"
#include "magFoam/Wrench.hpp"

#include <memory>
#include <span>
#include <string>

namespace mag {

class AppliedField {
public:
    virtual ~AppliedField() = default;

    // The time the next calls refer to (magFoam sets it every step).
    void setTime(double t) { time_ = t; }
    double time() const { return time_; }

    // B (T) and, when the span is non-empty, A (T m) at world points, added to
    // what is there.
    virtual void add(std::span<const Vec3> points, std::span<Vec3> B, std::span<Vec3> A = {}) const = 0;
    // The wrench on a magnetized body (ownEnergy: its energy in this field).
    virtual Wrench wrench(const Body& body) const = 0;
    // False for `none`: nothing to add anywhere.
    virtual bool active() const { return true; }
    // True when a table makes the field change in time (it then does work).
    virtual bool timeDependent() const { return false; }
    virtual std::string describe() const = 0;

    using Registry = mag::Registry<AppliedField>;
    static Registry& registry();
    // From constant/appliedField.yaml (a Dict holding `type:`).
    static std::unique_ptr<AppliedField> New(const Dict& dict);

    template <class T> struct Add {
        explicit Add(const std::string& name, TypeDoc doc = {}) {
            noteModelLayout(sizeof(Body), alignof(Quat));
            registry().add(
                name, [](const Dict& d) { return std::unique_ptr<AppliedField>(new T(d)); }, std::move(doc));
        }
    };

private:
    double time_ = 0;
};

} // namespace mag
