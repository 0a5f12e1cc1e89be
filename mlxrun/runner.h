// SPDX-License-Identifier: GPL-3.0-or-later
// What mlxrun does with a MeshLab 2022+ document, step by step. Every step throws MLException
// with a message for the user when it fails; main() turns that into exit status 1.
#pragma once
#include <QString>
#include <QStringList>

#include <common/ml_document/mesh_document.h>

#include "options.h"

namespace mlxrun {

// Loads every plugin (.so) in the folders, in name order.
void loadPlugins(const QStringList& folders);

// Writes each loaded filter's name, description and parameters to `path`.
void dumpFilters(const QString& path);

void openInputs(const QStringList& inputs, MeshDocument& md);

// Applies the script's filters in order: each starts from its defaults for this document, then
// takes the values the script gives. A parameter the filter does not have is an error.
void runScript(const QString& script, MeshDocument& md);

void saveOutputs(const std::vector<Output>& outputs, MeshDocument& md);

// Prints the log entries not printed yet (stdout), and appends them to log_file when given.
void flushLog(MeshDocument& md, const QString& log_file);

}  // namespace mlxrun
