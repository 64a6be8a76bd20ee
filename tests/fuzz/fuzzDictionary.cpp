// Fuzz target: the dictionary reader. Any input must end in a Dict or an
// InputError, within the reader's limits; every read a model could make of
// what it accepted must do the same.
#include <magFoam/Dictionary.hpp>
#include <magFoam/Error.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

namespace {

// Reads every key as each type a model asks for, and descends into mappings
// and lists (depth-limited: the reader already bounds the size).
void readAll(const mag::Dict& d, int depth) {
    for (const std::string& key : d.keys()) {
        auto attempt = [&](auto read) {
            try {
                read();
            } catch (const mag::InputError&) {
            }
        };
        attempt([&] { (void)d.get<double>(key); });
        attempt([&] { (void)d.get<int>(key); });
        attempt([&] { (void)d.get<bool>(key); });
        attempt([&] { (void)d.get<std::string>(key); });
        attempt([&] { (void)d.get<mag::Vec3>(key); });
        attempt([&] { (void)d.get<mag::Quat>(key); });
        attempt([&] { (void)d.get<std::vector<double>>(key); });
        attempt([&] { (void)d.get<std::vector<std::vector<double>>>(key); });
        attempt([&] { (void)d.get<std::vector<std::string>>(key); });
        attempt([&] { (void)d.where(key); });
        if (depth < 8) {
            attempt([&] { readAll(d.sub(key), depth + 1); });
            attempt([&] {
                for (const mag::Dict& item : d.list(key)) readAll(item, depth + 1);
            });
        }
    }
    try {
        d.reportUnused();
    } catch (const mag::InputError&) {
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        readAll(mag::Dict::fromString(text, "fuzz.yaml"), 0);
    } catch (const mag::InputError&) {
    }
    return 0;
}
