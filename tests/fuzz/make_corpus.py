#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz harnesses (tests/fuzz/corpus/<reader>/): small valid files of each format and
the hostile files of issue 18 as regression inputs. Run once; the files are kept in the repository."""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def put(reader, name, data):
    d = os.path.join(HERE, "corpus", reader)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def pcd_header(points, data, fields="x y z", sizes="4 4 4", types="F F F", counts="1 1 1"):
    return (f"# .PCD v0.7\nVERSION 0.7\nFIELDS {fields}\nSIZE {sizes}\nTYPE {types}\nCOUNT {counts}\n"
            f"WIDTH {points}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {points}\nDATA {data}\n").encode()


# PCD
put("pcd", "ascii", pcd_header(2, "ascii") + b"1 2 3\n4 5 6\n")
put("pcd", "binary_normals", pcd_header(1, "binary", "x y z normal_x normal_y normal_z", "4 4 4 4 4 4", "F F F F F F",
                                        "1 1 1 1 1 1") + struct.pack("<6f", 1, 2, 3, 0, 0, 1))
put("pcd", "compressed", pcd_header(2, "binary_compressed") + struct.pack("<II", 5, 24) + b"\x00\x00\xe0\x0e\x00")
put("pcd", "int8_uint8", pcd_header(1, "binary", "x y z", "8 8 8", "I U F") + struct.pack("<qQd", -5, 2**40 + 1, 1.5))
put("pcd", "regress_size888_body", pcd_header(2, "binary") + b"SIZE 8 8 8\n" + struct.pack("<6f", 1, 2, 3, 4, 5, 6))
put("pcd", "regress_blank_header_line", b"FIELDS x y z\n \t \nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nPOINTS 1\n"
    b"DATA ascii\n1 2 3\n")
put("pcd", "regress_uint8_minus1", pcd_header(1, "ascii", "x y z", "4 4 1", "F F U") + b"1 2 -1\n")
put("pcd", "regress_int32_3e11", pcd_header(1, "ascii", "x y z", "4 4 4", "F F I") + b"1 2 3e11\n")
put("pcd", "regress_bomb", pcd_header(100000000, "binary_compressed") + struct.pack("<II", 100, 1200000000) +
    bytes(100))
put("pcd", "padding_count", pcd_header(1, "ascii", "x y z _", "4 4 4 1", "F F F U", "1 1 1 4") + b"1 2 3 0 0 0 0\n")

# PLY
ply_ascii = ("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
             "element face 1\nproperty list uchar int vertex_indices\nend_header\n")
put("ply", "ascii", ply_ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
put("ply", "regress_extra_value", ply_ascii + "0 0 0 7\n1 0 0\n0 1 0\n3 0 1 2\n")
put("ply", "regress_trailing_lines", ply_ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0 0 0\n")
bin_header = ("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nelement face 1\n"
              "property list uchar int vertex_indices\nend_header\n").encode()
put("ply", "binary_normals", bin_header + struct.pack("<18f", 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1) +
    struct.pack("<B3i", 3, 0, 1, 2))
put("ply", "regress_big_polygon", b"ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\n"
    b"property float y\nproperty float z\nelement face 1\nproperty list ushort uchar vertex_indices\nend_header\n" +
    bytes(36) + struct.pack(">H", 2000) + bytes(2000))

# STL
put("stl", "ascii", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
    "endfacet\nendsolid t\n")
put("stl", "binary", bytes(80) + struct.pack("<I", 1) + struct.pack("<12f", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0) +
    b"\x00\x00")

# OBJ
put("obj", "mesh", "# t\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 2/1/1 4/1/1 3/1/1\nf -1 -2 -3\n")

# point lists
put("point_list", "xyz", "# x y z\n1 2 3\n4 5 6\n")
put("point_list", "normals", "x y z nx ny nz\n1,2,3,0,0,1\n4,5,6,0,1,0\n")

# CSV tables (and grids, features)
put("csv_table", "trajectory", "# trajectory\nx_mm,y_mm,z_mm,nx,ny,nz\n1,2,3,0,0,1\n4.5, 5 ,\"6\",0,1,0\n")
put("grid", "grid", "row,col,x_mm,y_mm,z_mm\n" + "".join(f"{r},{c},{10*c},{10*r},{(r*c)%3}\n" for r in range(4)
                                                         for c in range(4)))
put("features_csv", "features", "id,type,tx_mm,ty_mm,radius_mm\nH1,hole,5,100,4\nS1,point,-3,250,\n")
put("features_json", "features", '{"features": [{"id": "H1", "type": "hole", "tx_mm": 5, "ty_mm": 100, '
    '"radius_mm": 4}, {"id": "P1", "type": "polygon", "points_mm": [[0, 10], [5, 10], [5, 20]]}]}')
put("features_json", "regress_1e400", '{"features": [{"id": "H1", "type": "hole", "tx_mm": 1e400, "ty_mm": 5}]}')

# transforms and pairs
put("transform", "identity", "1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n")
put("transform", "rotation", "0 -1 0 10\n1 0 0 20\n0 0 1 30\n0 0 0 1\n")
put("pairs", "pairs", "0 0 0 1 1 1\n10 0 0 11 1 1\n0 10 0 1 11 1\n# comment\n0 0 10 1 1 11\n")
