// Shared by the depth-layer shaders. The layers of one vessel class are, per pixel of an
// orthographic view along +z, a column of depth slices:
//   occupancy: one bit per slice, set when the vessel surface passes through the cell
//              (pixel footprint x slice); every cell holding surface is set, and no other.
//   crossings: one bit per slice, toggled for every surface crossing of the pixel-centre ray;
//              the parity of the bits below a point says whether it is inside the vessel.
//   crossing halves and quarters: two bits per slice, toggled with the crossing by the quarter
//              of the slice it lies in (high bit, low bit): where a slice holds one crossing,
//              where in the slice the wall is, for the penetration's volume.
//   depth range: the lowest and highest occupied slice of the pixel (the paper's
//              nearest and farthest depth, a cuboid column per pixel).
// Buffers hold all classes one after another: [class][pixel][word].

uint ColumnBase(uint cls, uint pixel, uint words, uint pixels)
{
  return (cls * pixels + pixel) * words;
}
