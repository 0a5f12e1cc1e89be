// SPDX-License-Identifier: GPL-3.0-or-later
// mlxrun's command line, meshlabserver's (2020.09) flags: what to open, run, save and write.
#pragma once
#include <QString>
#include <QStringList>
#include <vector>

namespace mlxrun {

constexpr int kCurrentLayer = -1;
constexpr int kLastLayer = -2;

struct Output {
  QString path;
  // -o FILE -l N: layer N; -l x: the last layer (meshlabserver's spelling); else the current one.
  int layer = kCurrentLayer;
};

struct Options {
  QStringList inputs;            // -i FILE...: opened in order, each file one or more layers
  QString script;                // -s SCRIPT.mlx
  std::vector<Output> outputs;   // -o FILE [-l N]
  QString log_file;              // -l LOG (not right after -o)
  QString dump_file;             // -d DUMP: the loaded filters and their parameters
};

// Parses argv; on a mistake returns false with `why` set.
bool parseOptions(const QStringList& args, Options& options, QString& why);

extern const char* const kUsage;

}  // namespace mlxrun
