#include "magFoam/ArgList.hpp"

#include "magFoam/Error.hpp"
#include "magFoam/Log.hpp"
#include "magFoam/ModelDoc.hpp"
#include "magFoam/Plugins.hpp"

#include <exception>
#include <iostream>

namespace mag {

ArgList::ArgList(std::string app, std::string summary) : app_(std::move(app)), summary_(std::move(summary)) {
    options_ = {{"case", "DIR", "case folder (default: current folder)"},
                {"help", "", "print this usage and exit"},
                {"listModules", "", "list the available model types and their libraries, then exit"},
                {"doc", "[TYPE]", "the keys of model TYPE (types, defaults, units, example); alone: the types "
                                  "and what this app writes"},
                {"debug", "", "debug-level logging"}};
}

ArgList& ArgList::withThreads() {
    return option("threads", "N", "worker threads (overrides controlDict threads; 0 = all cores)");
}

ArgList& ArgList::withSchemes() {
    return option("schemes", "FILE", "use FILE (relative to the case) instead of system/magSchemes.yaml");
}

ArgList& ArgList::outputs(const std::string& text) {
    outputs_ = text;
    return *this;
}

ArgList& ArgList::option(const std::string& name, const std::string& argument, const std::string& help) {
    options_.push_back({name, argument, help});
    return *this;
}

ArgList& ArgList::positional(const std::string& name, const std::string& help, bool required) {
    positionalName_ = name, positionalHelp_ = help, positionalRequired_ = required;
    return *this;
}

void ArgList::printUsage() const {
    std::cout << "Usage: " << app_ << " [OPTIONS]";
    if (!positionalName_.empty())
        std::cout << (positionalRequired_ ? " " : " [") << positionalName_ << (positionalRequired_ ? "" : "]");
    std::cout << "\n\n" << summary_ << "\n\nOptions:\n";
    if (!positionalName_.empty()) std::cout << "  " << positionalName_ << "\n      " << positionalHelp_ << "\n";
    for (const auto& o : options_)
        std::cout << "  -" << o.name << (o.argument.empty() ? "" : " " + o.argument) << "\n      " << o.help << "\n";
}

bool ArgList::parse(int argc, char** argv) {
    log::init("info");
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a.size() > 1 && a[0] == '-' && !(a[1] >= '0' && a[1] <= '9')) {
            std::string name = a.substr(a[1] == '-' ? 2 : 1);
            const Option* opt = nullptr;
            for (const auto& o : options_)
                if (o.name == name) opt = &o;
            if (!opt) {
                std::cerr << app_ << ": unknown option '" << a << "' (see " << app_ << " -help)\n";
                exitCode_ = 2;
                return false;
            }
            if (opt->argument.empty() || opt->argument.front() == '[') {
                // A flag, or an optional value: the next word unless it is an option.
                const bool value = !opt->argument.empty() && i + 1 < argc && argv[i + 1][0] != '-';
                values_[name] = value ? argv[++i] : "";
            } else {
                if (i + 1 >= argc) {
                    std::cerr << app_ << ": option '" << a << "' needs a value " << opt->argument << "\n";
                    exitCode_ = 2;
                    return false;
                }
                values_[name] = argv[++i];
            }
        } else if (!positionalName_.empty() && !positional_) {
            positional_ = a;
        } else {
            std::cerr << app_ << ": unexpected argument '" << a << "' (see " << app_ << " -help)\n";
            exitCode_ = 2;
            return false;
        }
    }
    if (found("help")) {
        printUsage();
        return false;
    }
    if (found("debug")) log::init("debug");
    if (found("listModules")) {
        try {
            std::cout << plugins::listModules();
        } catch (const std::exception& e) {
            std::cerr << app_ << ": " << e.what() << "\n";
            exitCode_ = 1;
        }
        return false;
    }
    if (found("doc")) {
        try {
            if (get("doc").empty()) {
                std::cout << plugins::documentIndex();
                if (!outputs_.empty()) std::cout << "\n" << app_ << " writes:\n" << outputs_;
            } else {
                std::cout << plugins::documentType(get("doc"));
            }
        } catch (const std::exception& e) {
            std::cerr << app_ << ": " << e.what() << "\n";
            exitCode_ = 1;
        }
        return false;
    }
    if (found("threads")) {
        try {
            (void)threads();
        } catch (const InputError& e) {
            std::cerr << app_ << ": " << e.what() << "\n";
            exitCode_ = 2;
            return false;
        }
    }
    if (positionalRequired_ && !positional_) {
        std::cerr << app_ << ": missing " << positionalName_ << " (see " << app_ << " -help)\n";
        exitCode_ = 2;
        return false;
    }
    return true;
}

std::filesystem::path ArgList::caseDir() const { return found("case") ? values_.at("case") : "."; }

std::filesystem::path ArgList::schemesFile() const { return found("schemes") ? values_.at("schemes") : ""; }

std::string ArgList::get(const std::string& name) const {
    auto it = values_.find(name);
    return it == values_.end() ? std::string() : it->second;
}

std::optional<int> ArgList::threads() const {
    if (!found("threads")) return std::nullopt;
    const std::string v = get("threads");
    try {
        std::size_t pos = 0;
        int n = std::stoi(v, &pos);
        if (pos != v.size() || n < 0) throw std::invalid_argument(v);
        return n;
    } catch (const std::exception&) {
        throw InputError("-threads: expected a non-negative integer, got '" + v + "'");
    }
}

int runGuarded(const ArgList& args, const std::function<int(const ArgList&)>& body) {
    try {
        return body(args);
    } catch (const InputError& e) {
        std::cerr << "\n" << args.app() << ": error: " << e.what() << "\n";
        return 1;
    } catch (const StateError& e) {
        std::cerr << "\n" << args.app() << ": stopped: " << e.what() << "\n";
        return 1;
    } catch (const OutputError& e) {
        std::cerr << "\n" << args.app() << ": stopped: " << e.what() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "\n" << args.app() << ": internal error: " << e.what() << "\n";
        return 3;
    }
}

} // namespace mag
