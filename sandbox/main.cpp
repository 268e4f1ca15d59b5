#include "sandbox/lib/cli/sandbox_cli.h"

#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    return specula::sandbox::runCli(args, std::cout, std::cerr);
}
