// VirtualClock is header-only; this unit anchors the mock library.
#include "hal/mock/virtual_clock.hpp"
