#include "assetcooker/lib/cli/signal_guard.h"

#include "components/reflection_probe/writer/probe_folder.h"

#include <csignal>

extern "C" void speculaCookOnSignal(int) {
    specula::requestCancel();
}

namespace specula::cook {

SignalGuard::SignalGuard() {
    clearCancelRequest();
    oldInt_ = std::signal(SIGINT, speculaCookOnSignal);
    oldTerm_ = std::signal(SIGTERM, speculaCookOnSignal);
}

SignalGuard::~SignalGuard() {
    std::signal(SIGINT, oldInt_);
    std::signal(SIGTERM, oldTerm_);
}

} // namespace specula::cook
