/**
 * @class   vtkCloudFieldReader
 * @brief   a density field file, read by cloudvis's own readers
 *
 * vtkCloudFieldReader reads a field file in any format cloudvis reads (the table FieldFormats()
 * of app/fields/public/FieldIO.h: VTK XML image data, OpenVDB, NetCDF-CF, NRRD, MetaImage), with
 * the same protections against hostile files and the same result as `cloudvis render FILE`: a
 * float point-data array "density" on image data with the file's extent, origin, spacing and
 * direction. The plugin registers it for the files ParaView 5.11 cannot open, OpenVDB (.vdb) and
 * NetCDF named .nc4 or .cdf (docs/paraview.md, "Reading field files"); the other formats are read
 * by name (CloudFieldReader in Python) when what cloudvis reads is wanted rather than ParaView's
 * reader.
 *
 * The output's field data holds the units the field has, as `cloudvis info` reports them
 * (decided by cloudvis's one place for them, ResolveFieldValues in FieldIO.h, from what the file
 * declares): the strings "quantity" ("density" or "lwc"), "length_unit" ("none", "m", "km") and
 * "up" ("x", "y", "z"), and the numbers "effective_radius" (micrometres) and "droplet_number"
 * (per cm^3, 0 when none is declared). A NetCDF liquid water content in kg/m^3 is converted to
 * g/m^3, a mixing ratio made one with the air's density (NetCdfAirDensity.h, "auto"), and small
 * negative contents read as 0, as everywhere.
 *
 * A file that cannot be read (missing, truncated, corrupt, too large, an option it does not
 * take) gives one vtkErrorMacro naming the file and the problem and an empty output: a bad file
 * never ends the process (parsing that can crash runs in a forked child, IsolatedRead.h).
 *
 * The whole file is read once (again when the file name or an option changes) on every process,
 * and each process is given the sub-extent it requests (UPDATE_EXTENT, as ParaView splits an
 * image among MPI ranks): memory per rank is the whole field's.
 */
#ifndef vtkCloudFieldReader_h
#define vtkCloudFieldReader_h

#include "cloudvisParaViewModule.h"

#include <vtkImageAlgorithm.h>
#include <vtkSmartPointer.h> // for the field read

#include <string> // for the file name and options
#include <vector> // for the time steps

class vtkImageData;

class CLOUDVISPARAVIEW_EXPORT vtkCloudFieldReader : public vtkImageAlgorithm
{
public:
  static vtkCloudFieldReader* New();
  vtkTypeMacro(vtkCloudFieldReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The field file. Its format follows its extension (any case) unless Format is set. Default
   * none.
   */
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /**
   * The format, as a scene's field.format names it ("vdb", "netcdf", ...); empty: by the
   * extension. Default empty.
   */
  vtkSetStringMacro(Format);
  vtkGetStringMacro(Format);
  ///@}

  ///@{
  /**
   * The OpenVDB grid, NetCDF variable or VTK XML point array to read (field.array); empty: the
   * format's default (the grid "density", else the only float grid; ...). Default empty.
   */
  vtkSetStringMacro(ArrayName);
  vtkGetStringMacro(ArrayName);
  ///@}

  ///@{
  /**
   * The NetCDF time step to read, from 0 (field.time_step); -1: not given, the first. Default -1.
   * A file with a time axis of more than one step offers its steps to the pipeline (TIME_STEPS:
   * the time coordinate's values, else 0, 1, 2...), and a time the pipeline asks for (ParaView's
   * animation, UpdatePipeline(time)) chooses the step instead: the last at or before it. The
   * output's DATA_TIME_STEP is the time of the step read.
   */
  vtkSetMacro(TimeStep, int);
  vtkGetMacro(TimeStep, int);
  ///@}

  ///@{
  /**
   * Whether values a NetCDF file marks as missing are read as density 0 (field.missing "empty")
   * rather than refused. Default off (refused, with their count).
   */
  vtkSetMacro(MissingAsEmpty, bool);
  vtkGetMacro(MissingAsEmpty, bool);
  vtkBooleanMacro(MissingAsEmpty, bool);
  ///@}

  ///@{
  /**
   * The most voxels the field may have once read (field.max_voxels); a larger file is refused
   * before anything is allocated. Default 1073741824 (1024^3).
   */
  vtkSetMacro(MaximumVoxels, vtkTypeInt64);
  vtkGetMacro(MaximumVoxels, vtkTypeInt64);
  ///@}

  /**
   * Empty after a successful read, else the last read's problem (as reported by vtkErrorMacro).
   */
  const char* GetLastError() const { return this->LastError.c_str(); }

protected:
  vtkCloudFieldReader();
  ~vtkCloudFieldReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  char* Format = nullptr;
  char* ArrayName = nullptr;
  int TimeStep = -1;
  bool MissingAsEmpty = false;
  vtkTypeInt64 MaximumVoxels = vtkTypeInt64(1) << 30;

private:
  // Reads the file unless the field read last is still current; false (after vtkErrorMacro)
  // when it cannot be read.
  bool ReadFile();

  // The step of TimeValues at or before `time`.
  int StepAt(double time) const;

  // The whole file, as cloudvis read it, with its units (ResolveFieldValues) as field data.
  vtkSmartPointer<vtkImageData> Field;
  vtkMTimeType FieldTime = 0;          // this->GetMTime() when Field was read
  int FieldStep = -2;                  // the step Field holds (-1: the first, not given)
  int PipelineStep = -1;               // the step the pipeline's time chose; -1: none asked
  std::vector<double> TimeValues;      // the file's steps' times; empty: one step
  std::string LastError;

  vtkCloudFieldReader(const vtkCloudFieldReader&) = delete;
  void operator=(const vtkCloudFieldReader&) = delete;
};

#endif
