# Copied from the workplace gpu-bundle tool (tools/gpu_check/README.md says what this folder adds).
import subprocess, sys, os, re, json
LIB=os.environ['BUNDLE_LIBS']
SYS={'libc.so.6','libm.so.6','ld-linux-x86-64.so.2','libEGL.so.1','libGLESv2.so.2','libGLdispatch.so.0','libGLX.so.0','libdl.so.2','libpthread.so.0','librt.so.1','libresolv.so.2','libutil.so.1'}
_cache={}
def needed(path):
    if path in _cache: return _cache[path]
    out=subprocess.run(['readelf','-d',path],capture_output=True,text=True).stdout
    r=re.findall(r'\(NEEDED\)\s+Shared library: \[(.+?)\]',out)
    _cache[path]=r; return r
def closure(roots, stubs):
    seen=set(); order=[]
    st=list(roots)
    while st:
        p=st.pop()
        for n in needed(p):
            if n in SYS or n in seen: continue
            seen.add(n)
            if n in stubs: continue
            st.append(os.path.join(LIB,n))
    return seen
