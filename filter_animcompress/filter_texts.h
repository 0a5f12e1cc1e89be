// SPDX-License-Identifier: GPL-3.0-or-later
// The filters' names and descriptions, shared by the 2020.09 and 2022+ shells: a name is the
// filter's id in .mlx scripts (MeshLab matches the menu text), so both must spell it the same.
#pragma once
#include <QString>

namespace animc::meshlab {

enum FilterId { kCompressFilter, kReconstructionErrorFilter, kImportFilter };

QString filterTitle(int id);
QString filterDescription(int id);

}  // namespace animc::meshlab
