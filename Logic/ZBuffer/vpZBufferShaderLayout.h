#ifndef vpZBufferShaderLayout_h
#define vpZBufferShaderLayout_h

// What the z-buffer's host code and its shaders (Shaders/*.comp) share: the push constant blocks,
// the records of the storage buffers the host writes or reads, and the constants both sides
// must agree on. Declared once here on the host side and once in the shaders; ShaderLayoutFields()
// lists every field with its offset, and the ZBufferShaderLayout test holds each one to the offset
// glslang's reflection reads from the shader (so a field moved on one side only fails a test, not
// a patient's answer).

#include "vpDepthLayerGrid.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vp
{
namespace zbuffer
{
/// Words per class in the query state (QueryProximityCommon.glsl).
constexpr std::uint32_t StateStride = 32;
/// Tiles per coarse tile along x and y (CoarseTiles in QueryProximityCommon.glsl).
constexpr int CoarseTiles = 4;
/// A tile's edge in pixels (SummarizeTiles.comp's TilePx for the fine tiles; the grid's own).
constexpr int TilePx = DepthLayerGrid::TilePx;
/// The query's stages (QueryProximityCommon.glsl).
constexpr std::int32_t VisitOrderedTiles = 0, SelectTiles = 1, VisitListedTiles = 2, SelectTilesPerAnswer = 3,
                       VisitHostListedTiles = 4;
/// Bits of a tile range's code that name the pixel of a tile, and of a coarse tile, whose column
/// has the slice above them (TilePixelBits, CoarsePixelBits in QueryProximityCommon.glsl).
constexpr unsigned TilePixelBits = 6, CoarsePixelBits = 10;
/// A slot's items in the host's list per point of the slot, and the mark of an item that is a
/// lane (HostListItemsPerPoint, LaneItem in QueryProximityCommon.glsl).
constexpr std::uint32_t HostListItemsPerPoint = 8;
constexpr std::uint32_t LaneItem = 0x80000000u;

/// RasterizeLayers.comp's Parameters.
struct RasterParameters
{
  float Origin[3];
  float InvPixelMm;
  float InvSliceMm;
  std::int32_t Nx, Ny, Nz, Words;
  std::uint32_t Class, FirstTriangle, TriangleCount;
};

/// SummarizeColumns.comp's Parameters.
struct ColumnParameters
{
  std::uint32_t Pixels, Classes, Words, RangeStride;
};

/// SummarizeTiles.comp's Parameters.
struct TileParameters
{
  std::int32_t Nx, Ny, TilesX, TilesY;
  std::uint32_t Classes, RangeStride;
  std::int32_t TilePx;
  std::uint32_t Offset;
};

/// QueryProximity.comp's and QueryProximityPerPixel.comp's Parameters.
struct QueryParameters
{
  float PixelMm;
  float SliceMm;
  float RangeMm;
  float HalfDiagonalMm;
  float BinWidthMm;
  std::int32_t Bins, Nx, Ny, Nz, Words, TilesX, TilesY, OrderCount, PaperMode;
  std::uint32_t RangeStride;
  std::int32_t Classes;
  std::int32_t DirectionalLanes;
  std::int32_t FirstEntry, EndEntry;
  std::int32_t LaneSlots;
  std::int32_t Stage, TilesPerGroup;
  std::int32_t OrderReach, CoarseCount;
  std::int32_t FirstPoint;
  std::int32_t AnswerCount;
};

/// ReduceProximity.comp's Parameters.
struct ReduceParameters
{
  std::uint32_t Step, Answers, OrderCount, FirstAnswer;
};

/// What a query reads per point (Points in QueryProximityCommon.glsl, two vec4 a point): the tip
/// in grid units, then the unit axis.
struct PointRecord
{
  float Tip[4];
  float Axis[4];
};

/// Per point and class, the answer's ceiling and the order table's entries within it (Ceilings
/// in QueryProximityCommon.glsl, a uvec2 each: the float's bits, then the count).
struct AnswerCeiling
{
  float Mm;
  std::uint32_t Entries;
};

/// One item of the host's list of a few tips' tiles (HostTileList in QueryProximityCommon.glsl, a
/// uvec2 each): its answer (point x classes + class), and its entry in the order table or
/// LaneItem plus a lane. A slot's first item holds the number of items after it.
struct HostListItem
{
  std::uint32_t Answer;
  std::uint32_t Entry;
};

/// One field of a block as the shaders see it: "Parameters.Nx" at offset 20 in RasterParameters,
/// or an element of a storage buffer's array ("Point", stride 16).
struct ShaderField
{
  const char* Block;  ///< the host struct
  std::string Name;   ///< as glslang reflects it: Parameters.<member>, or the array's name
  std::size_t Offset; ///< the member's offset, or the array's stride
  bool Stride;        ///< Offset is an array stride
};

/// Every field the host shares with a shader, and the shaders whose block it is.
struct ShaderBlock
{
  const char* Block;
  std::size_t Size;
  std::vector<std::string> Shaders;
};

inline std::vector<ShaderBlock> ShaderBlocks()
{
  return {
    { "RasterParameters", sizeof(RasterParameters), { "RasterizeLayers.comp" } },
    { "ColumnParameters", sizeof(ColumnParameters), { "SummarizeColumns.comp" } },
    { "TileParameters", sizeof(TileParameters), { "SummarizeTiles.comp" } },
    { "QueryParameters", sizeof(QueryParameters), { "QueryProximity.comp", "QueryProximityPerPixel.comp" } },
    { "ReduceParameters", sizeof(ReduceParameters), { "ReduceProximity.comp" } },
    { "PointRecord", sizeof(PointRecord), { "QueryProximity.comp", "QueryProximityPerPixel.comp" } },
    { "AnswerCeiling", sizeof(AnswerCeiling), { "QueryProximity.comp", "QueryProximityPerPixel.comp" } },
    { "HostListItem", sizeof(HostListItem), { "QueryProximity.comp", "QueryProximityPerPixel.comp" } },
  };
}

#define VP_SHADER_FIELD(block, member) ShaderField{ #block, "Parameters." #member, offsetof(block, member), false }
inline std::vector<ShaderField> ShaderLayoutFields()
{
  return {
    VP_SHADER_FIELD(RasterParameters, Origin),
    VP_SHADER_FIELD(RasterParameters, InvPixelMm),
    VP_SHADER_FIELD(RasterParameters, InvSliceMm),
    VP_SHADER_FIELD(RasterParameters, Nx),
    VP_SHADER_FIELD(RasterParameters, Ny),
    VP_SHADER_FIELD(RasterParameters, Nz),
    VP_SHADER_FIELD(RasterParameters, Words),
    VP_SHADER_FIELD(RasterParameters, Class),
    VP_SHADER_FIELD(RasterParameters, FirstTriangle),
    VP_SHADER_FIELD(RasterParameters, TriangleCount),
    VP_SHADER_FIELD(ColumnParameters, Pixels),
    VP_SHADER_FIELD(ColumnParameters, Classes),
    VP_SHADER_FIELD(ColumnParameters, Words),
    VP_SHADER_FIELD(ColumnParameters, RangeStride),
    VP_SHADER_FIELD(TileParameters, Nx),
    VP_SHADER_FIELD(TileParameters, Ny),
    VP_SHADER_FIELD(TileParameters, TilesX),
    VP_SHADER_FIELD(TileParameters, TilesY),
    VP_SHADER_FIELD(TileParameters, Classes),
    VP_SHADER_FIELD(TileParameters, RangeStride),
    VP_SHADER_FIELD(TileParameters, TilePx),
    VP_SHADER_FIELD(TileParameters, Offset),
    VP_SHADER_FIELD(QueryParameters, PixelMm),
    VP_SHADER_FIELD(QueryParameters, SliceMm),
    VP_SHADER_FIELD(QueryParameters, RangeMm),
    VP_SHADER_FIELD(QueryParameters, HalfDiagonalMm),
    VP_SHADER_FIELD(QueryParameters, BinWidthMm),
    VP_SHADER_FIELD(QueryParameters, Bins),
    VP_SHADER_FIELD(QueryParameters, Nx),
    VP_SHADER_FIELD(QueryParameters, Ny),
    VP_SHADER_FIELD(QueryParameters, Nz),
    VP_SHADER_FIELD(QueryParameters, Words),
    VP_SHADER_FIELD(QueryParameters, TilesX),
    VP_SHADER_FIELD(QueryParameters, TilesY),
    VP_SHADER_FIELD(QueryParameters, OrderCount),
    VP_SHADER_FIELD(QueryParameters, PaperMode),
    VP_SHADER_FIELD(QueryParameters, RangeStride),
    VP_SHADER_FIELD(QueryParameters, Classes),
    VP_SHADER_FIELD(QueryParameters, DirectionalLanes),
    VP_SHADER_FIELD(QueryParameters, FirstEntry),
    VP_SHADER_FIELD(QueryParameters, EndEntry),
    VP_SHADER_FIELD(QueryParameters, LaneSlots),
    VP_SHADER_FIELD(QueryParameters, Stage),
    VP_SHADER_FIELD(QueryParameters, TilesPerGroup),
    VP_SHADER_FIELD(QueryParameters, OrderReach),
    VP_SHADER_FIELD(QueryParameters, CoarseCount),
    VP_SHADER_FIELD(QueryParameters, FirstPoint),
    VP_SHADER_FIELD(QueryParameters, AnswerCount),
    VP_SHADER_FIELD(ReduceParameters, Step),
    VP_SHADER_FIELD(ReduceParameters, Answers),
    VP_SHADER_FIELD(ReduceParameters, OrderCount),
    VP_SHADER_FIELD(ReduceParameters, FirstAnswer),
    // Storage buffer records are arrays of vectors in the shaders: their strides.
    ShaderField{ "PointRecord", "Point", sizeof(PointRecord) / 2, true },
    ShaderField{ "AnswerCeiling", "AnswerCeiling", sizeof(AnswerCeiling), true },
    ShaderField{ "HostListItem", "HostItem", sizeof(HostListItem), true },
  };
}
#undef VP_SHADER_FIELD
} // namespace zbuffer
} // namespace vp

#endif
