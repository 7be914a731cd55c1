#include "core/memory_budget.h"

#include <unistd.h>

namespace relief {

double defaultMemoryBudgetMB() {
    const double bytes = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGE_SIZE));
    return bytes > 0 ? 0.75 * bytes / 1e6 : 1e6;
}

}  // namespace relief
