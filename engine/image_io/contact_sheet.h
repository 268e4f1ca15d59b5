#pragma once
// Picture layouts for reports: a labelled grid of tiles and a side-by-side strip.
#include "engine/image/image.h"

#include <string>
#include <vector>

namespace specula {

// Lays `tiles` out in a grid of `columns` columns, each resized to `tileWidth` pixels wide
// (aspect kept), separated by a small gap on a dark background, with `labels[i]` (if given)
// written under tile i. Returns linear RGB. Labels are drawn with the first system font
// OpenImageIO can open (DejaVu Sans on Debian: fonts-dejavu-core); without one the sheet
// has no text. Empty tiles leave their cell blank.
Image contactSheet(const std::vector<Image>& tiles, const std::vector<std::string>& labels,
                   int columns, int tileWidth);

// The images next to each other, left to right, top-aligned, `gap` background pixels apart;
// the result has the largest channel count of the inputs (missing channels 0, alpha 1).
Image hconcat(const std::vector<Image>& images, int gap = 0);

// Whether contactSheet can draw labels on this machine.
bool contactSheetHasFont();

} // namespace specula
