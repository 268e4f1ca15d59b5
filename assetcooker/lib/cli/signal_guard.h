#pragma once
// SIGINT/SIGTERM during a cooker command (Ctrl-C; scancel, which sends SIGTERM to a Slurm
// task) only request a cancel: the work stops at its next check and throws Cancelled, every
// writer's temporary is removed, and what the command would replace stays as it was. Without
// the guard the default handlers kill the process between a write and its rename.
namespace specula::cook {

// Installs the cancelling handlers for its lifetime (the previous ones are restored after)
// and clears any earlier cancel request.
class SignalGuard {
public:
    SignalGuard();
    ~SignalGuard();
    SignalGuard(const SignalGuard&) = delete;
    SignalGuard& operator=(const SignalGuard&) = delete;

private:
    using Handler = void (*)(int);
    Handler oldInt_, oldTerm_;
};

} // namespace specula::cook
