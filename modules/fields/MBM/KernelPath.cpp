// Runtime choice of the blocked field kernel's copy (see KernelPath.hpp).
#include "KernelPath.hpp"
#include "PolyhedronBlocks.hpp"

#include <magFoam/Error.hpp>

#include <spdlog/spdlog.h>

#include <atomic>
#include <cstdlib>

namespace mag::mbm {

namespace {

using blocks::BlockKernel;

// The copies in this build, narrowest first.
std::vector<const BlockKernel*> compiledKernels() {
    std::vector<const BlockKernel*> k{&blocks::baseline::kernel()};
#if defined(MAG_MBM_KERNEL_V4)
    // (unless the build's flags already give AVX-512: one copy per instruction set)
    if (std::string_view(k[0]->name) != blocks::x86_64_v4::kernel().name)
        k.push_back(&blocks::x86_64_v4::kernel());
#endif
    return k;
}

const std::vector<const BlockKernel*>& kernels() {
    static const std::vector<const BlockKernel*> k = compiledKernels();
    return k;
}

#if defined(MAG_MBM_KERNEL_V4)
// Whether the CPU (and the OS, which must save the AVX-512 registers: the builtins
// check XCR0) runs x86-64-v4 code: its AVX-512 subsets, and the x86-64-v3 features
// every such CPU has besides.
bool cpuHasX86_64_v4() {
    static const bool has = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
               __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") &&
               __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx2") &&
               __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2");
    }();
    return has;
}
#endif

bool supported(const BlockKernel* k) {
#if defined(MAG_MBM_KERNEL_V4)
    if (k == &blocks::x86_64_v4::kernel()) return cpuHasX86_64_v4();
#endif
    return k == &blocks::baseline::kernel();
}

// "auto, avx2, avx512" (all compiled) or only those this CPU runs.
std::string validNames(bool onlySupported) {
    std::string names = "auto";
    for (const BlockKernel* k : kernels())
        if (!onlySupported || supported(k)) names += std::string(", ") + k->name;
    return names;
}

// The copy named `name` ("auto": the widest supported); `origin` names the request in
// errors ("MAG_KERNEL", "setKernelPath").
const BlockKernel* find(std::string_view name, std::string_view origin) {
    if (name == "auto") {
        for (auto k = kernels().rbegin(); k != kernels().rend(); ++k)
            if (supported(*k)) return *k;
    }
    for (const BlockKernel* k : kernels()) {
        if (name != k->name) continue;
        if (supported(k)) return k;
        throw InputError(std::string(origin) + ": MBM kernel path '" + std::string(name) +
                         "' needs AVX-512 (x86-64-v4: avx512f, avx512bw, avx512cd, avx512dq, "
                         "avx512vl), which this CPU lacks; valid here: " + validNames(true));
    }
    throw InputError(std::string(origin) + ": unknown MBM kernel path '" + std::string(name) +
                     "'; valid paths: " + validNames(false));
}

// The copy in use; null until the first evaluate() or setKernelPath().
std::atomic<const BlockKernel*> selected{nullptr};

const BlockKernel* fromEnvironment() {
    const char* env = std::getenv("MAG_KERNEL");
    const std::string_view name = env && *env ? env : "auto";
    const BlockKernel* k = find(name, "MAG_KERNEL");
    spdlog::debug("MBM field kernel: {} ({} points per block; MAG_KERNEL={})", k->name, k->width,
                  name);
    return k;
}

} // namespace

const BlockKernel& blocks::current() {
    if (const BlockKernel* k = selected.load(std::memory_order_acquire)) return *k;
    // First use: MAG_KERNEL, read once (an invalid value throws here, and again at the
    // next call); a setKernelPath() meanwhile wins.
    static const BlockKernel* const initial = fromEnvironment();
    const BlockKernel* expected = nullptr;
    selected.compare_exchange_strong(expected, initial, std::memory_order_acq_rel);
    return *selected.load(std::memory_order_acquire);
}

std::vector<std::string> kernelPaths() {
    std::vector<std::string> names;
    for (const BlockKernel* k : kernels()) names.emplace_back(k->name);
    return names;
}

bool kernelPathSupported(std::string_view path) {
    for (const BlockKernel* k : kernels())
        if (path == k->name) return supported(k);
    return false;
}

std::string kernelPath() { return blocks::current().name; }

int kernelWidth() { return blocks::current().width; }

void setKernelPath(std::string_view path) {
    const BlockKernel* k = find(path, "setKernelPath");
    selected.store(k, std::memory_order_release);
    spdlog::debug("MBM field kernel: {} ({} points per block; set)", k->name, k->width);
}

} // namespace mag::mbm
