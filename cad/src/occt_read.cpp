// STEP and IGES into one OpenCASCADE shape, in millimetres.

#include <algorithm>
#include <cctype>
#include <sstream>
#include <stdexcept>
#include <string>

#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_ProgressIndicator.hxx>
#include <STEPControl_Reader.hxx>
#include <Interface_Check.hxx>
#include <Interface_InterfaceModel.hxx>
#include <StepBasic_NamedUnit.hxx>
#include <StepBasic_SiUnit.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TCollection_HAsciiString.hxx>

#include "occt_progress.h"
#include "occt_shape.h"

namespace conform::cad {

namespace {

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

// Millimetres per unit for the names STEP and IGES files use; 0 when unknown.
double mm_per_unit_named(const std::string& name) {
  const std::string u = upper(name);
  if (u == "MM" || u == "MILLIMETRE" || u == "MILLIMETER") return 1.0;
  if (u == "CM" || u == "CENTIMETRE" || u == "CENTIMETER") return 10.0;
  if (u == "M" || u == "METRE" || u == "METER") return 1000.0;
  if (u == "KM" || u == "KILOMETRE" || u == "KILOMETER") return 1e6;
  if (u == "UM" || u == "MICRON" || u == "MICROMETRE" || u == "MICROMETER") return 1e-3;
  if (u == "IN" || u == "INCH" || u == "INCHES") return 25.4;
  if (u == "FT" || u == "FOOT" || u == "FEET") return 304.8;
  if (u == "MI" || u == "MILE") return 1609344.0;
  if (u == "MIL") return 0.0254;
  if (u == "UIN" || u == "MICROINCH") return 2.54e-5;
  return 0.0;
}

// IGES Global section, parameter 14 (unit flag).
double mm_per_iges_unit_flag(int flag) {
  switch (flag) {
    case 1: return 25.4;
    case 2: return 1.0;
    case 4: return 304.8;
    case 5: return 1609344.0;
    case 6: return 1000.0;
    case 7: return 1e6;
    case 8: return 0.0254;
    case 9: return 1e-3;
    case 10: return 10.0;
    case 11: return 2.54e-5;
    default: return 0.0;
  }
}

// The entity's text as written in the file ("#12=(LENGTH_UNIT()...SI_UNIT(.BOGUS.,.METRE.));"), at most 120 bytes.
std::string entity_text(const conform_cad_request& request, const std::string& label) {
  const std::string bytes(request.bytes, request.size);
  for (std::size_t at = bytes.find(label); at != std::string::npos; at = bytes.find(label, at + 1)) {
    std::size_t after = at + label.size();
    while (after < bytes.size() && (bytes[after] == ' ' || bytes[after] == '\t')) ++after;
    if (after >= bytes.size() || bytes[after] != '=') continue;  // a reference to it, or a longer label (#123)
    const std::size_t end = std::min({bytes.find(';', at), at + 120, bytes.size()});
    std::string text = bytes.substr(at, end - at + (end < bytes.size() && bytes[end] == ';' ? 1 : 0));
    for (char& c : text) c = (c == '\n' || c == '\r') ? ' ' : c;
    return text;
  }
  return label;
}

// OpenCASCADE reads an SI unit whose prefix or name is not one of STEP's (SI_UNIT(.BOGUS.,.METRE.)) as no prefix,
// i.e. metres: a 60 mm block becomes 60 m without a word. Its syntactic check of that entity records the failure;
// any failed unit entity stops the read, naming the entity as written.
void check_step_units(const STEPControl_Reader& reader, const conform_cad_request& request) {
  const Handle(Interface_InterfaceModel) model = reader.Model();
  if (model.IsNull()) return;
  for (int i = 1; i <= model->NbEntities(); ++i) {
    const Handle(Standard_Transient) entity = model->Value(i);
    const bool unit = entity->IsKind(STANDARD_TYPE(StepBasic_NamedUnit)) ||
                      entity->IsKind(STANDARD_TYPE(StepBasic_SiUnit));
    const bool unknown = model->IsUnknownEntity(i) || model->IsErrorEntity(i);
    if (!unit && !unknown) continue;
    const Handle(Interface_Check)& check = model->Check(i, Standard_True);
    if (check.IsNull() || !check->HasFailed()) continue;
    const std::string text = entity_text(request, model->StringLabel(entity)->ToCString());
    if (!unit && upper(text).find("UNIT") == std::string::npos) continue;
    throw std::runtime_error("its unit " + text + " is not valid (" + check->CFail(1) +
                             "): conform reads no length unit it does not know");
  }
}

// OpenCASCADE prints its traces on stdout, which is the JSON channel: no printers.
void silence_messages() { Message::DefaultMessenger()->ChangePrinters().Clear(); }

ReadShape read_step(const conform_cad_request& request, const ProgressSink& progress) {
  STEPControl_Reader reader;
  std::istringstream stream(std::string(request.bytes, request.size));
  if (reader.ReadStream(request.path, stream) != IFSelect_RetDone) {
    throw std::runtime_error("OpenCASCADE cannot parse it as STEP (ISO 10303-21)");
  }
  check_step_units(reader, request);
  ReadShape out;
  TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
  reader.FileUnits(lengths, angles, solid_angles);
  out.file_unit = lengths.IsEmpty() ? "MM" : lengths.First().ToCString();
  for (int i = 2; i <= lengths.Length(); ++i) {
    if (upper(lengths.Value(i).ToCString()) != upper(out.file_unit)) {
      throw std::runtime_error(std::string("it mixes length units (") + out.file_unit + " and " +
                               lengths.Value(i).ToCString() + ")");
    }
  }
  out.mm_per_file_unit = mm_per_unit_named(out.file_unit);
  const Handle(ProgressIndicator) indicator = new ProgressIndicator(progress, "read CAD");
  reader.TransferRoots(indicator->Start());
  if (reader.NbShapes() == 0) throw std::runtime_error("no shapes could be transferred from it");
  out.shape = reader.OneShape();
  return out;
}

ReadShape read_iges(const conform_cad_request& request, const ProgressSink& progress) {
  IGESControl_Reader reader;
  if (reader.ReadFile(request.path) != IFSelect_RetDone) {
    throw std::runtime_error("OpenCASCADE cannot parse it as IGES");
  }
  ReadShape out;
  const IGESData_GlobalSection& global = reader.IGESModel()->GlobalSection();
  const Handle(TCollection_HAsciiString) name = global.UnitName();
  out.file_unit = name.IsNull() ? "" : name->ToCString();
  const int flag = global.UnitFlag();
  // Flags 1 to 11 are IGES's (5.3, Global parameter 14); 3 means "named in parameter 15". Any other flag is not a
  // unit, whatever OpenCASCADE would scale it by.
  if (flag < 1 || flag > 11) {
    throw std::runtime_error("its IGES unit flag " + std::to_string(flag) + " (unit name '" + out.file_unit +
                             "') is not valid (1 to 11): conform reads no length unit it does not know");
  }
  out.mm_per_file_unit = flag == 3 ? mm_per_unit_named(out.file_unit) : mm_per_iges_unit_flag(flag);
  // A flag and a name that disagree (flag 9, micrometres, named MM) make a 30 mm part 0.03 mm or the other way round:
  // which one the writer meant cannot be known.
  const double named = mm_per_unit_named(out.file_unit);
  if (flag != 3 && named != 0.0 && named != out.mm_per_file_unit) {
    throw std::runtime_error("its IGES unit flag " + std::to_string(flag) + " and its unit name '" + out.file_unit +
                             "' are not valid together (they disagree): conform reads no length unit it is unsure of");
  }
  if (out.file_unit.empty()) out.file_unit = "flag " + std::to_string(flag);
  const Handle(ProgressIndicator) indicator = new ProgressIndicator(progress, "read CAD");
  reader.TransferRoots(indicator->Start());
  if (reader.NbShapes() == 0) throw std::runtime_error("no shapes could be transferred from it");
  out.shape = reader.OneShape();
  return out;
}

}  // namespace

ReadShape read_shape(const conform_cad_request& request, const ProgressSink& progress) {
  silence_messages();
  // Lengths in millimetres whatever the file's unit: OpenCASCADE scales on transfer.
  Interface_Static::SetCVal("xstep.cad.unit", "MM");
  progress("read CAD", 0.0);
  ReadShape out = request.format == CONFORM_CAD_STEP ? read_step(request, progress) : read_iges(request, progress);
  if (out.shape.IsNull()) throw std::runtime_error("it holds no geometry");
  if (out.mm_per_file_unit == 0.0) {
    throw std::runtime_error("its length unit '" + out.file_unit + "' is not one conform knows");
  }
  progress("read CAD", 1.0);
  return out;
}

}  // namespace conform::cad
