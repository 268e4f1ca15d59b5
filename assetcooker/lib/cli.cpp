#include "cli.h"

#include "assetcooker/lib/bake_command.h"
#include "assetcooker/lib/inspect.h"
#include "assetcooker/lib/plan_command.h"
#include "engine/core/error.h"

#include <exception>

namespace specula::cook {

namespace {

constexpr std::string_view kToolUsage = "usage: specula-cook <subcommand> [options] [args]\n"
                                        "       specula-cook <subcommand> --help\n";

bool isHelp(const std::string& a) {
    return a == "--help" || a == "-h";
}

// Splits a subcommand's arguments into positionals, rejecting any flag it does not know.
// Subcommands with flags extend this with their own table when they need one.
std::vector<std::string> positionalsOnly(std::span<const std::string> args) {
    std::vector<std::string> pos;
    bool flagsDone = false;
    for (const std::string& a : args) {
        if (!flagsDone && a == "--") {
            flagsDone = true;
        } else if (!flagsDone && a.size() > 1 && a[0] == '-') {
            throw UsageError{"unknown option '" + a + "'"};
        } else {
            pos.push_back(a);
        }
    }
    return pos;
}

int runInspect(std::span<const std::string> args, std::ostream& out, std::ostream&) {
    const auto pos = positionalsOnly(args);
    if (pos.size() != 1)
        throw UsageError{pos.empty() ? "inspect needs a FILE" : "inspect takes exactly one FILE"};
    out << inspectScene(pos[0]).dump(2) << '\n';
    return kExitOk;
}

void printToolHelp(std::ostream& out) {
    out << kToolUsage << "\nBakes reflection probes from glTF scenes.\n\nsubcommands:\n";
    for (const Subcommand& s : subcommands()) {
        out << "  " << s.name;
        for (std::size_t i = s.name.size(); i < 10; ++i)
            out << ' ';
        out << s.summary << '\n';
    }
    out << "\noptions:\n  -h, --help  show this help\n";
}

// Errors are one line on stderr: what(), which already names the file and the field.
std::string firstLine(const std::string& s) {
    const auto n = s.find('\n');
    return n == std::string::npos ? s : s.substr(0, n);
}

} // namespace

const std::vector<Subcommand>& subcommands() {
    static const std::vector<Subcommand> table = {
        {"inspect", "print what a glTF/GLB file holds as one JSON object",
         "usage: specula-cook inspect [options] FILE\n"
         "\n"
         "Loads FILE (.gltf or .glb, Draco-compressed meshes included) and prints one JSON\n"
         "object to stdout: meshes, primitives, vertices, triangles (each mesh counted once,\n"
         "however many nodes instance it), bounds {min, max} in world space, extensionsUsed,\n"
         "nodes, materials and warnings.\n"
         "\n"
         "options:\n"
         "  -h, --help  show this help\n"
         "\n"
         "exit status: 0 ok, 1 FILE could not be loaded, 2 bad command line\n",
         runInspect},
        {"bake", "bake a scene's reflection probe into a cooked folder", kBakeUsage, runBake},
        {"plan", "print the effect plan of a scene's probe (what it needs, and why)", kPlanUsage,
         runPlan},
    };
    return table;
}

int runCli(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
    if (args.empty()) {
        err << kToolUsage << "specula-cook: error: missing subcommand (try --help)\n";
        return kExitUsage;
    }
    if (isHelp(args[0])) {
        printToolHelp(out);
        return kExitOk;
    }
    const Subcommand* sub = nullptr;
    for (const Subcommand& s : subcommands())
        if (s.name == args[0]) sub = &s;
    if (!sub) {
        err << kToolUsage << "specula-cook: error: "
            << (args[0].starts_with("-") ? "unknown option '" : "unknown subcommand '") << args[0]
            << "' (try --help)\n";
        return kExitUsage;
    }
    const auto rest = args.subspan(1);
    for (const std::string& a : rest) {
        if (a == "--") break;
        if (isHelp(a)) {
            out << sub->usage;
            return kExitOk;
        }
    }
    try {
        return sub->run(rest, out, err);
    } catch (const UsageError& e) {
        err << "usage: specula-cook " << sub->name << " --help\n"
            << "specula-cook " << sub->name << ": error: " << e.message << '\n';
        return kExitUsage;
    } catch (const Cancelled& e) {
        err << "specula-cook " << sub->name << ": cancelled: " << firstLine(e.what()) << '\n';
        return kExitCancelled;
    } catch (const Error& e) {
        err << "specula-cook " << sub->name << ": error: " << firstLine(e.what()) << '\n';
    } catch (const std::exception& e) {
        err << "specula-cook " << sub->name << ": error: " << firstLine(e.what()) << '\n';
    }
    return kExitFailure;
}

} // namespace specula::cook
