// Compiled by the parent-project test: a host's file that includes Specula's component headers.
#include "components/reflection_probe/distance/distance_probe.h"

int hostProbeUser() {
    return 0;
}
