#!/usr/bin/env python3
"""Reads a DXF file with ezdxf, as a CAD program would, and prints what it holds as JSON.

Usage: read_dxf.py FILE

The independent reader of tests/cad/export_test.cpp for cad/export_dxf. It loads the file, runs
ezdxf's audit (the check ezdxf's own "ezdxf audit" command runs), and prints one JSON object:
the DXF version, $INSUNITS, the audit's errors and fixes, the layers of the LAYER table, the
entity counts per layer and type, and every LWPOLYLINE (its vertices in world coordinates,
transformed from its OCS by ezdxf), LINE, POINT and 3DFACE with its coordinates.
Exits with 0 when the file loads, 2 when ezdxf cannot read it (the reason on stderr).
"""
import json
import sys

import ezdxf


def xyz(vector):
    return [vector[0], vector[1], vector[2]]


def main():
    path = sys.argv[1]
    try:
        doc = ezdxf.readfile(path)
    except (IOError, ezdxf.DXFStructureError) as error:
        print(f"{path}: {error}", file=sys.stderr)
        return 2
    auditor = doc.audit()
    result = {
        "version": doc.dxfversion,
        "units": doc.header.get("$INSUNITS", None),
        "audit_errors": [f"{entry.code}: {entry.message}" for entry in auditor.errors],
        "audit_fixes": [f"{entry.code}: {entry.message}" for entry in auditor.fixes],
        "layers": sorted(layer.dxf.name for layer in doc.layers),
        "counts": {},
        "polylines": [],
        "lines": [],
        "points": [],
        "faces": [],
    }
    for entity in doc.modelspace():
        layer = entity.dxf.layer
        kind = entity.dxftype()
        per_layer = result["counts"].setdefault(layer, {})
        per_layer[kind] = per_layer.get(kind, 0) + 1
        if kind == "LWPOLYLINE":
            result["polylines"].append(
                {"layer": layer, "closed": entity.closed, "wcs": [xyz(v) for v in entity.vertices_in_wcs()]}
            )
        elif kind == "LINE":
            result["lines"].append({"layer": layer, "start": xyz(entity.dxf.start), "end": xyz(entity.dxf.end)})
        elif kind == "POINT":
            result["points"].append({"layer": layer, "position": xyz(entity.dxf.location)})
        elif kind == "3DFACE":
            result["faces"].append({"layer": layer, "vertices": [xyz(v) for v in entity.wcs_vertices()]})
    json.dump(result, sys.stdout)
    return 0


if __name__ == "__main__":
    sys.exit(main())
