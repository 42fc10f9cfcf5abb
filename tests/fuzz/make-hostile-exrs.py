#!/usr/bin/env python3
# Writes the hand-made hostile EXRs of tests/fuzz/regressions-exr/ (docs/hardening.md): headers
# that lie about their windows, small on disk. Run once in that directory; the output is checked in.
import struct, sys
def attr(name, typ, data): return name.encode()+b'\0'+typ.encode()+b'\0'+struct.pack('<i',len(data))+data
def chlist(names, ptype=2):
    d=b''
    for n in names: d+=n.encode()+b'\0'+struct.pack('<iB3xii',ptype,0,1,1)
    return d+b'\0'
def header(names, box, disp, comp=1, ptype=2, extra=b''):
    h=b'\x76\x2f\x31\x01'+struct.pack('<i',2)
    h+=attr('channels','chlist',chlist(names,ptype))
    h+=attr('compression','compression',bytes([comp]))
    h+=attr('dataWindow','box2i',struct.pack('<4i',*box))
    h+=attr('displayWindow','box2i',struct.pack('<4i',*disp))
    h+=attr('lineOrder','lineOrder',b'\0')
    h+=attr('pixelAspectRatio','float',struct.pack('<f',1))
    h+=attr('screenWindowCenter','v2f',struct.pack('<2f',0,0))
    h+=attr('screenWindowWidth','float',struct.pack('<f',1))
    h+=extra
    return h+b'\0'
def write(name, data): open(name,'wb').write(data)
# 1. 20000 x 20000 RGBA float, ZIP (16 lines a chunk): 6.4 GB to read; the header and its 1250
# chunk offsets, 10 kB, and no pixel data.
h=header(['A','B','G','R'],(0,0,19999,19999),(0,0,19999,19999),comp=3)
write('huge-data-window.exr', h+b''.join(struct.pack('<Q',len(h)+8*1250+i*100) for i in range(1250)))
# 2. A data window with min > max (negative size).
h=header(['B','G','R'],(10,10,0,0),(0,0,9,9))
write('inverted-data-window.exr', h+struct.pack('<Q',len(h)+8))
# 3. A display window of 60000 x 60000 (merge's frame: 57 GB) around a 1x1 data window, with a
# glint:settings_hash so that merge gets as far as allocating the frame.
extra=attr('glint:settings_hash','string',b'abc')
h=header(['B','G','R'],(0,0,0,0),(0,0,59999,59999),comp=0,extra=extra)
row=struct.pack('<ii',0,12)+struct.pack('<3f',1,1,1)
write('huge-display-window-merge.exr', h+struct.pack('<Q',len(h)+8)+row)
# 4. A data window at negative coordinates outside the display window (valid EXR).
h=header(['B','G','R'],(-7,-5,-6,-5),(0,0,1,1),comp=0,extra=extra)
row=struct.pack('<ii',-5,24)+struct.pack('<6f',*[0.5]*6)
write('data-window-outside-display-window.exr', h+struct.pack('<Q',len(h)+8)+row)
# 5. A string attribute declaring 900 MB in a 400-byte file: OpenEXR allocated the declared size
# before reading it (glint_fuzz_exr found the same with 918 MB strings).
lie=b'comments\0string\0'+struct.pack('<i',900000000)+b'abc'
h=header(['B','G','R'],(0,0,0,0),(0,0,0,0),comp=0,extra=lie)
write('string-attribute-declaring-900-MB.exr', h)
# 6. A whole 2x1 frame (with a glint:settings_hash, so that merge takes it as its one crop) whose
# second pixel is NaN: merge copied it into the frame, exit 0. Glint writes no NaN.
h=header(['B','G','R'],(0,0,1,0),(0,0,1,0),comp=0,extra=extra)
nan=struct.unpack('<f',struct.pack('<I',0x7fc00000))[0]
row=struct.pack('<ii',0,24)+struct.pack('<6f',0.5,nan,0.5,nan,0.5,nan)
write('nan-pixel-copied-into-the-merged-frame.exr', h+struct.pack('<Q',len(h)+8)+row)
# 7. A 500000 x 1 RGBA float image in DWAB's 256-line blocks: OpenEXR sizes a block's buffers at
# 2 GB (glint_fuzz_exr found a 2.16 GB allocation); header only.
h=header(['A','B','G','R'],(0,0,499999,0),(0,0,499999,0),comp=9)
write('line-block-of-2-GB.exr', h+struct.pack('<Q',len(h)+8))
# 8. The same 50000 pixels wide: blocks of 205 MB, within the limit, and no pixel data.
h=header(['A','B','G','R'],(0,0,49999,0),(0,0,49999,0),comp=9)
write('line-block-of-205-MB.exr', h+struct.pack('<Q',len(h)+8))
# 9. Tiled, one channel, 4096 x 4096 tiles: OpenEXR caches a row of tiles across the data window
# as floats, and DWA sizes its scratch by it. 1000000 pixels wide (ZIP): a 15.6 GB cache from a
# 2.4 kB file; 12000 wide (DWAA, one all-zero 88-byte DWA chunk): rows of 192 MiB, within the
# limit.
def tiled(name, width, comp):
    h=header(['A'],(0,0,width-1,0),(0,0,width-1,0),comp=comp)
    h=h[:4]+struct.pack('<i',2|0x200)+h[8:-1]+attr('tiles','tiledesc',struct.pack('<IIB',4096,4096,0))+b'\0'
    n=(width+4095)//4096
    chunk=struct.pack('<5i',0,0,0,0,88)+b'\0'*88
    write(name, h+b''.join(struct.pack('<Q',len(h)+8*n) for _ in range(n))+chunk)
tiled('tiled-row-of-15-GB.exr', 1000000, 3)
tiled('tiled-dwaa-row-of-192-MiB.exr', 12000, 8)
