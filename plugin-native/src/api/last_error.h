// The thread-local message behind drape_last_error(), for entry points outside src/api.
#pragma once

#include "drape/drape.h"

namespace drape {

/// Sets this thread's drape_last_error() message and returns status (DRAPE_OK clears it).
drape_status set_last_error(drape_status status, const char* message);

}  // namespace drape
