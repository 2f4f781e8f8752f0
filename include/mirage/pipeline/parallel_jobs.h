// SPDX-License-Identifier: MIT
// Runs independent jobs 0..total-1 on a pool of threads (the Monte-Carlo drivers' runs). Each job
// writes only its own result slot, so results do not depend on the number of threads.
#pragma once

#include <functional>

namespace mirage::pipeline {

/// Calls job(i) for every i in [0, total) on `threads` threads (0 = all cores), then progress(done,
/// total) after each job (from the worker thread; the callback must be thread-safe). The first
/// exception thrown by a job stops handing out jobs and is rethrown here.
void RunJobs(int total, int threads, const std::function<void(int)>& job,
             const std::function<void(int, int)>& progress);

}  // namespace mirage::pipeline
