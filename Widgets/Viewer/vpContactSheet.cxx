#include "vpContactSheet.h"

#include <vtkImageData.h>
#include <vtkImageResize.h>
#include <vtkNew.h>
#include <vtkStdString.h>
#include <vtkTextProperty.h>
#include <vtkTextRenderer.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

namespace vp
{
namespace
{
const int GapPx = 12;
/// A caption's lines under each thumbnail: a key frame's reasons in words take two or three at
/// 420 pixels ("tip closest to the portal vein, 0.4 mm; the instrument's first contact with ...").
const int CaptionLines = 3;
const int CaptionLinePx = 19;
const int CaptionPx = CaptionLines * CaptionLinePx + 8;
const unsigned char Background[3] = { 24, 26, 34 };

/// Copies src (RGB or RGBA, unsigned char) into dst (RGB) with its lower left corner at (x, y),
/// clipped to dst.
void Paste(vtkImageData* dst, vtkImageData* src, int x, int y)
{
  int d[3], e[6];
  dst->GetDimensions(d);
  src->GetExtent(e); // a rendered string's extent need not start at 0
  const int channels = src->GetNumberOfScalarComponents();
  for (int j = e[2]; j <= e[3]; ++j)
  {
    for (int i = e[0]; i <= e[1]; ++i)
    {
      const int tx = x + i - e[0], ty = y + j - e[2];
      if (tx < 0 || ty < 0 || tx >= d[0] || ty >= d[1])
      {
        continue;
      }
      auto* from = static_cast<unsigned char*>(src->GetScalarPointer(i, j, e[4]));
      auto* to = static_cast<unsigned char*>(dst->GetScalarPointer(tx, ty, 0));
      const double alpha = channels == 4 ? from[3] / 255.0 : 1.0;
      for (int k = 0; k < 3; ++k)
      {
        to[k] = static_cast<unsigned char>(alpha * from[std::min(k, channels - 1)] + (1.0 - alpha) * to[k]);
      }
    }
  }
}
/// The caption's words in lines no wider than widthPx, at most CaptionLines (the last ends in
/// "..." when words are left over).
std::vector<std::string> WrapCaption(vtkTextRenderer* text, vtkTextProperty* style, const std::string& caption, int widthPx)
{
  auto fits = [&](const std::string& line) {
    int box[4] = { 0, 0, 0, 0 };
    return !text->GetBoundingBox(style, vtkStdString(line), box, 72) || box[1] - box[0] <= widthPx;
  };
  std::vector<std::string> lines(1);
  std::size_t start = 0;
  while (start < caption.size())
  {
    std::size_t end = caption.find(' ', start);
    const std::string word = caption.substr(start, end == std::string::npos ? std::string::npos : end - start);
    start = end == std::string::npos ? caption.size() : end + 1;
    const std::string longer = lines.back().empty() ? word : lines.back() + " " + word;
    if (fits(longer) || lines.back().empty())
    {
      lines.back() = longer;
    }
    else if (lines.size() < static_cast<std::size_t>(CaptionLines))
    {
      lines.push_back(word);
    }
    else
    {
      lines.back() += " ...";
      break;
    }
  }
  return lines;
}
} // namespace

vtkSmartPointer<vtkImageData> MakeContactSheet(const std::vector<ContactSheetEntry>& entries, int columns, int thumbWidthPx)
{
  columns = std::max(1, std::min(columns, static_cast<int>(std::max<std::size_t>(1, entries.size()))));
  int thumbHeightPx = 1;
  for (const ContactSheetEntry& e : entries)
  {
    int dims[3];
    e.Image->GetDimensions(dims);
    thumbHeightPx = std::max(thumbHeightPx, dims[1] * thumbWidthPx / std::max(1, dims[0]));
  }
  const int rows = static_cast<int>((entries.size() + columns - 1) / columns);
  const int cellW = thumbWidthPx + GapPx, cellH = thumbHeightPx + CaptionPx + GapPx;
  auto sheet = vtkSmartPointer<vtkImageData>::New();
  sheet->SetDimensions(columns * cellW + GapPx, std::max(1, rows) * cellH + GapPx, 1);
  sheet->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  int dims[3];
  sheet->GetDimensions(dims);
  auto* pixels = static_cast<unsigned char*>(sheet->GetScalarPointer());
  for (int p = 0; p < dims[0] * dims[1]; ++p)
  {
    std::memcpy(pixels + 3 * p, Background, 3);
  }
  vtkTextRenderer* text = vtkTextRenderer::GetInstance();
  vtkNew<vtkTextProperty> style;
  style->SetFontSize(15);
  style->SetColor(1.0, 1.0, 1.0);
  style->SetFontFamilyToArial();
  style->SetJustificationToLeft();
  style->SetVerticalJustificationToBottom();
  for (std::size_t n = 0; n < entries.size(); ++n)
  {
    const int col = static_cast<int>(n) % columns, row = static_cast<int>(n) / columns;
    // Image rows count from the bottom: the first row of thumbnails at the top.
    const int x = GapPx + col * cellW;
    const int top = dims[1] - GapPx - row * cellH;
    vtkNew<vtkImageResize> resize;
    int size[3];
    entries[n].Image->GetDimensions(size);
    resize->SetInputData(entries[n].Image);
    resize->SetOutputDimensions(thumbWidthPx, std::max(1, size[1] * thumbWidthPx / std::max(1, size[0])), 1);
    resize->Update();
    int thumb[3];
    resize->GetOutput()->GetDimensions(thumb);
    Paste(sheet, resize->GetOutput(), x, top - thumb[1]);
    if (!text)
    {
      continue;
    }
    const std::vector<std::string> lines = WrapCaption(text, style, entries[n].Caption, thumbWidthPx);
    for (std::size_t l = 0; l < lines.size(); ++l)
    {
      vtkNew<vtkImageData> caption;
      int textDims[2] = { 0, 0 };
      if (text->RenderString(style, vtkStdString(lines[l]), caption, textDims, 72))
      {
        Paste(sheet, caption, x, top - thumb[1] - static_cast<int>(l + 1) * CaptionLinePx);
      }
    }
  }
  return sheet;
}
} // namespace vp
