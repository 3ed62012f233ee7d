// The RGL material database's `.bsdf` files (Dupuy & Jakob 2018; the format pbrt-v4's `measured`
// material and Mitsuba's `measured` plugin read): a "tensor_file" container, little-endian:
//   12 bytes "tensor_file\0", version (uint8 major 1, uint8 minor 0), uint32 field count, then per
//   field: uint16 name length, the name, uint16 rank, uint8 dtype (1 uint8, 2 int8, 3 uint16,
//   4 int16, 5 uint32, 6 int32, 7 uint64, 8 int64, 9 float16, 10 float32, 11 float64), uint64 offset
//   of its data in the file, rank x uint64 shape; the data, row-major, at the offsets.
// The fields a measured BSDF needs (scene/measured_bsdf.h says what each holds): theta_i, phi_i
// (float32 [n]), ndf, sigma (float32 [ny, nx]), vndf (float32 [phi_i, theta_i, ny, nx]),
// luminance (float32 [phi_i, theta_i, n, n]), spectra (float32 [phi_i, theta_i, wavelengths, n, n])
// with wavelengths (float32 [k]) or, in a file without them, rgb (float32 [phi_i, theta_i, 3, n, n]),
// description (uint8 [k]) and jacobian (uint8 [1]). Other fields are allowed and skipped.
//
// Hardening: the reader never trusts a size. The field table is read with every count checked
// against the bytes left; each field's byte size is computed without overflow and its data must
// lie inside the file, after the field table and apart from every other field's; dtypes and ranks
// are checked per field, shapes against each other; values must be finite, non-negative where
// they are densities or areas, and every sampling slice must have mass (MeasuredBsdfTables::check).
// Anything wrong is a ParseError "file: what is wrong" (with the byte offset where it helps);
// allocations never exceed a small multiple of the file's size.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "scene/measured_bsdf.h"

namespace phos::io {

// The tables of the file's bytes; `path` names the file in errors.
scene::MeasuredBsdfTables parse_rgl_bsdf(std::string_view bytes, const std::string& path);
// The file read, checked and built into interpolants. Throws ParseError (path: message) for a file
// that cannot be opened or is malformed.
std::shared_ptr<const scene::MeasuredBsdf> read_rgl_bsdf(const std::string& path);

// The tensor file of `tables` (which must pass check()): every field pbrt-v4 reads, spectra with
// wavelengths when the tables have them, rgb when they have it, each field's data 8-byte aligned
// after the field table, as the RGL tools lay them out.
std::string rgl_bsdf_bytes(const scene::MeasuredBsdfTables& tables);
// Writes rgl_bsdf_bytes(tables) to `path`; throws InputError when it cannot.
void write_rgl_bsdf(const std::string& path, const scene::MeasuredBsdfTables& tables);

}  // namespace phos::io
