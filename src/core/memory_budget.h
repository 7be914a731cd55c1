#pragma once
// How much memory relief may use when a scene does not say ([limits]
// max_memory_mb): one figure for every stage and command, the nets', the
// refinement's, a film's POV-Rays' and the images relief diff compares.
namespace relief {

/// Three quarters of this machine's physical memory, in MB.
double defaultMemoryBudgetMB();

}  // namespace relief
