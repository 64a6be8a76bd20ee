// Command-line handling shared by every app (OpenFOAM's argList):
//   -case DIR      the case folder (default .)
//   -help          usage, options and exit
//   -listModules   the model types of every registry and their libraries
//   -doc [TYPE]    a model type's keys (ModelDoc.hpp); alone: the types and
//                  the files the app writes, with their columns and units
//   -debug         debug-level logging
// and, for the apps where they mean something (withThreads, withSchemes):
//   -threads N     override controlDict threads
//   -schemes FILE  use FILE instead of system/magSchemes.yaml (model swaps)
// Apps declare their own extra options; unknown options are errors.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mag {

class ArgList {
public:
    struct Option {
        std::string name;       // without the dash
        std::string argument;   // empty for flags, else the value's name
        std::string help;
    };

    ArgList(std::string app, std::string summary);
    ArgList& option(const std::string& name, const std::string& argument, const std::string& help);
    ArgList& positional(const std::string& name, const std::string& help, bool required);
    ArgList& withThreads();
    ArgList& withSchemes();
    // What the app writes (files, columns, units), printed by -doc alone.
    ArgList& outputs(const std::string& text);

    // Parse argv. Returns false when the app should exit right away (after
    // -help or -listModules, with `exitCode()` set; usage errors set 2).
    bool parse(int argc, char** argv);
    int exitCode() const { return exitCode_; }

    std::filesystem::path caseDir() const;
    // -schemes FILE (empty when not given): replaces system/magSchemes.yaml.
    std::filesystem::path schemesFile() const;
    bool found(const std::string& name) const { return values_.count(name) != 0; }
    std::string get(const std::string& name) const;
    std::optional<std::string> positionalValue() const { return positional_; }
    std::optional<int> threads() const;

    const std::string& app() const { return app_; }
    void printUsage() const;

private:
    std::string app_, summary_, outputs_;
    std::vector<Option> options_;
    std::string positionalName_, positionalHelp_;
    bool positionalRequired_ = false;
    std::optional<std::string> positional_;
    std::map<std::string, std::string> values_;
    int exitCode_ = 0;
};

// Run an app's body, turning InputError/StateError into one clear message and
// a non-zero exit (1), so bad input never crashes.
int runGuarded(const ArgList& args, const std::function<int(const ArgList&)>& body);

} // namespace mag
