// The --dicomweb options of `vots serve`, parsed into server::DicomWebService with pacs' parsers.
#include "ServeDicomWeb.h"

#include "vots/fit/Error.h"
#include "vots/pacs/DicomWebAuth.h"
#include "vots/pacs/DicomWebUrl.h"

#include <CLI/CLI.hpp>

#include <map>
#include <regex>
#include <utility>

namespace vots::cli {
namespace {

/// "NAME=VALUE" split, NAME checked to be a plain identifier of at most 32 characters.
std::pair<std::string, std::string> namedValue(const std::string& text, const char* option) {
    const auto equals = text.find('=');
    static const std::regex plainName("[A-Za-z0-9_-]{1,32}");
    if (equals == std::string::npos || !std::regex_match(text.substr(0, equals), plainName))
        throw fit::InputError(std::string(option) +
                              ": expected NAME=VALUE with NAME of 1..32 letters, digits, '_' or '-'");
    return {text.substr(0, equals), text.substr(equals + 1)};
}

} // namespace

void addServeDicomWebOptions(CLI::App& command, ServeDicomWebArgs& args) {
    command.add_option(
        "--dicomweb", args.services,
        "A PACS the viewer may browse and open series from, as NAME=dicomweb+http(s)://HOST:PORT/"
        "ROOT (repeatable; docs/PACS.md). Retrieved series are kept in the cache folder");
    command.add_option("--dicomweb-auth", args.auths,
                       "NAME=FILE: the credentials for that PACS, the file's one line 'basic USER:PASSWORD' "
                       "or 'bearer TOKEN' (repeatable)");
    command.add_option("--dicomweb-ca", args.cas,
                       "NAME=FILE: PEM certificates to verify that https PACS with (repeatable; default: the "
                       "system's)");
    command
        .add_option("--dicomweb-cache-gb", args.cacheGb,
                    "GiB of retrieved PACS series kept in the cache folder's dicomweb/; the least recently "
                    "opened are removed beyond (the newest always stays)")
        ->check(CLI::Range(0, 1 << 20))
        ->capture_default_str();
}

std::vector<server::DicomWebService> dicomWebServicesOf(const ServeDicomWebArgs& args) {
    std::vector<server::DicomWebService> services;
    std::map<std::string, std::size_t> byName;
    for (const std::string& text : args.services) {
        auto [name, url] = namedValue(text, "--dicomweb");
        if (byName.count(name)) throw fit::InputError("--dicomweb: the name '" + name + "' is given twice");
        byName[name] = services.size();
        services.push_back({name, pacs::parseDicomWebEndpoint(url), {}});
    }
    const auto serviceNamed = [&](const std::string& name, const char* option) -> server::DicomWebService& {
        const auto it = byName.find(name);
        if (it == byName.end())
            throw fit::InputError(std::string(option) + ": no --dicomweb " + name + "=URL names that PACS");
        return services[it->second];
    };
    for (const std::string& text : args.auths) {
        const auto [name, file] = namedValue(text, "--dicomweb-auth");
        server::DicomWebService& service = serviceNamed(name, "--dicomweb-auth");
        service.access.auth = pacs::readDicomWebAuthFile(file);
    }
    for (const std::string& text : args.cas) {
        const auto [name, file] = namedValue(text, "--dicomweb-ca");
        serviceNamed(name, "--dicomweb-ca").access.caFile = file;
    }
    return services;
}

} // namespace vots::cli
