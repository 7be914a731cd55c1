#pragma once
// The executors behind execute::run (execute.h): each runs the tasks, whose
// plans the caller has read (plans[i] is task i's).
#include "execute/execute.h"
#include "plan/plan.h"

namespace relief::execute {

Result runLocal(const std::vector<Task>& tasks, const std::vector<const plan::RenderPlan*>& plans,
                const Options& options, const std::function<void(const Progress&)>& progress);

Result runSlurm(const std::vector<Task>& tasks, const std::vector<const plan::RenderPlan*>& plans,
                const Options& options, const std::function<void(const Progress&)>& progress);

}  // namespace relief::execute
