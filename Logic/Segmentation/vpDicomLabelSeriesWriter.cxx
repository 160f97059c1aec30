#include "vpDicomLabelSeriesWriter.h"

#include "vpInputError.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcuid.h>

#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <cmath>
#include <filesystem>
#include <sstream>

namespace vp
{
namespace
{
std::string Join(const double* values, int count)
{
  std::ostringstream out;
  out.precision(10);
  for (int i = 0; i < count; ++i)
  {
    out << (i ? "\\" : "") << values[i];
  }
  return out.str();
}

void Check(const OFCondition& status, const std::string& folder)
{
  if (status.bad())
  {
    throw InputError(folder, std::string("cannot write DICOM: ") + status.text());
  }
}
} // namespace

ImageIdentity DicomLabelSeriesWriter::NewIdentity(const std::string& patientName)
{
  char study[100], frame[100];
  dcmGenerateUniqueIdentifier(study, SITE_STUDY_UID_ROOT);
  dcmGenerateUniqueIdentifier(frame);
  ImageIdentity identity;
  identity.PatientName = patientName;
  identity.StudyUid = study;
  identity.FrameOfReferenceUid = frame;
  return identity;
}

void DicomLabelSeriesWriter::Write(const LabelGrid& grid, const std::string& folder, const std::string& seriesName,
  const std::vector<int>& fileOrder, const std::string& prefix)
{
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec)
  {
    throw InputError(folder, "cannot create folder: " + ec.message());
  }
  int dims[3];
  grid.Labels->GetDimensions(dims);
  const auto& m = grid.IjkToLps;
  double spacing[3], axis[3][3];
  for (int c = 0; c < 3; ++c)
  {
    spacing[c] = grid.SpacingMm(c);
    for (int r = 0; r < 3; ++r)
    {
      axis[c][r] = m[4 * r + c] / spacing[c];
    }
  }
  const double orientation[6] = { axis[0][0], axis[0][1], axis[0][2], axis[1][0], axis[1][1], axis[1][2] };
  const double pixelSpacing[2] = { spacing[1], spacing[0] }; // between rows, between columns
  const bool wide = grid.Labels->GetScalarType() != VTK_UNSIGNED_CHAR;
  char series[100];
  dcmGenerateUniqueIdentifier(series, SITE_SERIES_UID_ROOT);
  const ImageIdentity own = grid.Identity.FrameOfReferenceUid.empty() ? NewIdentity("") : grid.Identity;
  const char* study = own.StudyUid.c_str();
  const char* frame = own.FrameOfReferenceUid.c_str();
  const std::string patient = grid.Identity.PatientName.empty() ? "VesselProximity^" + seriesName : grid.Identity.PatientName;
  const std::size_t perSlice = static_cast<std::size_t>(dims[0]) * dims[1];
  vtkDataArray* scalars = grid.Labels->GetPointData()->GetScalars();

  for (int k = 0; k < dims[2]; ++k)
  {
    DcmFileFormat file;
    DcmDataset* d = file.getDataset();
    char instance[100];
    dcmGenerateUniqueIdentifier(instance, SITE_INSTANCE_UID_ROOT);
    double position[3];
    for (int r = 0; r < 3; ++r)
    {
      position[r] = m[4 * r + 2] * k + m[4 * r + 3];
    }
    Check(d->putAndInsertString(DCM_SOPClassUID, UID_CTImageStorage), folder);
    Check(d->putAndInsertString(DCM_SOPInstanceUID, instance), folder);
    Check(d->putAndInsertString(DCM_StudyInstanceUID, study), folder);
    Check(d->putAndInsertString(DCM_SeriesInstanceUID, series), folder);
    Check(d->putAndInsertString(DCM_FrameOfReferenceUID, frame), folder);
    Check(d->putAndInsertString(DCM_Modality, "CT"), folder);
    Check(d->putAndInsertString(DCM_PatientName, patient.c_str()), folder);
    Check(d->putAndInsertString(DCM_SeriesDescription, seriesName.c_str()), folder);
    Check(d->putAndInsertString(DCM_InstanceNumber, std::to_string(k + 1).c_str()), folder);
    Check(d->putAndInsertString(DCM_ImagePositionPatient, Join(position, 3).c_str()), folder);
    Check(d->putAndInsertString(DCM_ImageOrientationPatient, Join(orientation, 6).c_str()), folder);
    Check(d->putAndInsertString(DCM_PixelSpacing, Join(pixelSpacing, 2).c_str()), folder);
    Check(d->putAndInsertString(DCM_SliceThickness, Join(&spacing[2], 1).c_str()), folder);
    Check(d->putAndInsertUint16(DCM_SamplesPerPixel, 1), folder);
    Check(d->putAndInsertString(DCM_PhotometricInterpretation, "MONOCHROME2"), folder);
    Check(d->putAndInsertUint16(DCM_Rows, static_cast<Uint16>(dims[1])), folder);
    Check(d->putAndInsertUint16(DCM_Columns, static_cast<Uint16>(dims[0])), folder);
    Check(d->putAndInsertUint16(DCM_BitsAllocated, wide ? 16 : 8), folder);
    Check(d->putAndInsertUint16(DCM_BitsStored, wide ? 16 : 8), folder);
    Check(d->putAndInsertUint16(DCM_HighBit, wide ? 15 : 7), folder);
    Check(d->putAndInsertUint16(DCM_PixelRepresentation, 0), folder);
    if (wide)
    {
      std::vector<Uint16> pixels(perSlice);
      for (std::size_t i = 0; i < perSlice; ++i)
      {
        pixels[i] = static_cast<Uint16>(scalars->GetTuple1(static_cast<vtkIdType>(k * perSlice + i)));
      }
      Check(d->putAndInsertUint16Array(DCM_PixelData, pixels.data(), static_cast<unsigned long>(perSlice)), folder);
    }
    else
    {
      const auto* pixels = static_cast<const Uint8*>(grid.Labels->GetScalarPointer()) + k * perSlice;
      Check(d->putAndInsertUint8Array(DCM_PixelData, pixels, static_cast<unsigned long>(perSlice)), folder);
    }
    const int number = fileOrder.empty() ? k : fileOrder.at(static_cast<std::size_t>(k));
    const std::string path = folder + "/" + prefix + std::to_string(number);
    Check(file.saveFile(path.c_str(), EXS_LittleEndianExplicit), path);
  }
}
} // namespace vp
