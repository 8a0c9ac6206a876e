# pvpython: saves one .vtp in every XML data mode ParaView's SaveData offers
# (the "Save Data" dialog's Data Mode, Encode Appended Data and Compressor
# Type), for tests/paraview_saved_files.sh.
#   pvpython paraview_save_modes.py SOURCE.vtp OUT_FOLDER
import os
import sys

from paraview.simple import SaveData, XMLPolyDataReader

source, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)
reader = XMLPolyDataReader(FileName=[source])
SaveData(os.path.join(out, "ascii.vtp"), proxy=reader, DataMode="Ascii")
for compressor in ("None", "ZLib", "LZ4"):
    c = compressor.lower()
    SaveData(os.path.join(out, f"binary_{c}.vtp"), proxy=reader, DataMode="Binary", CompressorType=compressor)
    for encode in (0, 1):
        name = f"appended_{'base64' if encode else 'raw'}_{c}.vtp"
        SaveData(os.path.join(out, name), proxy=reader, DataMode="Appended", EncodeAppendedData=encode,
                 CompressorType=compressor)
print(len(os.listdir(out)), "files in", out)
