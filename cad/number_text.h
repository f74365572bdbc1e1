#pragma once
// Numbers as text for the CAD formats: the shortest decimal that reads back as the same double,
// in fixed notation (no exponent, which some OBJ and DXF readers refuse), with a decimal point
// even when whole ("250.0"). 512000.1 stays "512000.1", a UTM coordinate keeps every bit (far
// below the 0.01 mm a survey needs), and nothing is padded with digits the double does not hold.

#include <string>

namespace plumb::cad {

// Appends `value`, which must be finite (asserted), to `out`. Thread-safe.
void appendNumber(std::string& out, double value);

// appendNumber into a new string.
std::string numberText(double value);

}  // namespace plumb::cad
