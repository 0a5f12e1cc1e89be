// SPDX-License-Identifier: Apache-2.0
// The project's only implementation of its quality and size figures (CLI, MeshLab plugins and
// benchmarks all call it, so published numbers agree). Definitions follow the literature and
// match seqmetrics.py of the shared tools beside the repository, the independent numpy
// cross-check (tests/cli/metrics_crosscheck.sh). Text and JSON of these figures: report/.
#pragma once
// MetricsAccumulator, SequenceMetrics and sizeFigures() are public: animc/animc.h.
#include "animc/animc.h"
