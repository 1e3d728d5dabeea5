#!/usr/bin/env python3
# Copied from the workplace gpu-bundle tool (tools/gpu_check/README.md says what this folder adds).
"""Generate stub shared objects for heavy leaf libraries ShadeLab never calls into.
Each stub has the same soname and exports the same dynamic symbols (same version nodes,
same default/hidden versions, same type and size) as the real library, except symbols that
a kept (real) library also exports: those are left to the real one so that vague-linkage
C++ symbols (typeinfo, template statics, inline functions) are never interposed.
Functions: 'mov $idx,%edi; jmp __stub_called' (returns 0; STUB_TRACE=1 logs calls to stderr).
A few functions return a pointer to an empty string (version queries that get strlen'd).
Data: zero-filled, same size (bss/tbss)."""
import subprocess, sys, os, re
from closure import closure, needed, SYS
LIB = os.environ['BUNDLE_LIBS']  # the resolved libraries, one file per soname (pack.sh fills it)
SYSLIBS = ['/lib/x86_64-linux-gnu/libc.so.6', '/lib/x86_64-linux-gnu/libm.so.6']
RET_EMPTY_STR = set(os.environ.get('STUB_RET_STR', '').split(',')) - {''}

def dynsyms(path):
    out = subprocess.run(['readelf', '--dyn-syms', '-W', path], capture_output=True, text=True).stdout
    res = []
    for line in out.splitlines():
        f = line.split()
        if len(f) < 8 or not f[0].endswith(':') or not f[0][:-1].isdigit(): continue
        num, val, size, typ, bind, vis, ndx, name = f[:8]
        if ndx == 'UND': continue
        ver, dflt = None, True
        if '@@' in name: name, ver = name.split('@@', 1)
        elif '@' in name: name, ver = name.split('@', 1); dflt = False
        size = int(size, 16) if size.startswith('0x') else int(size)
        res.append(dict(name=name, ver=ver, dflt=dflt, size=size, type=typ, bind=bind, vis=vis, ndx=ndx))
    return res

def verdefs(path):
    out = subprocess.run(['readelf', '-V', '-W', path], capture_output=True, text=True).stdout
    m = re.search(r"Version definition section.*?\n(.*?)(?:\n\n|\Z)", out, re.S)
    if not m: return []
    nodes = []
    for line in m.group(1).splitlines():
        mm = re.search(r'Flags: (\S+)\s+Index: (\d+)\s+Cnt: \d+\s+Name: (\S+)', line)
        if mm:
            if mm.group(1) == 'BASE': continue
            nodes.append([mm.group(3), []]); continue
        mm = re.search(r'Parent \d+: (\S+)', line)
        if mm and nodes: nodes[-1][1].append(mm.group(1))
    return nodes

def asm_name(s):
    return '"%s"' % s if re.search(r'[^A-Za-z0-9_.$]', s) else s

def gen(soname, outdir, exclude):
    path = os.path.join(LIB, soname)
    syms = dynsyms(path)
    nodes = verdefs(path)
    node_names = {n for n, _ in nodes}
    base = re.sub(r'[^A-Za-z0-9]', '_', soname)
    S, mapping, script = [], [], {n: [] for n, _ in nodes}
    S.append('\t.text')
    data, tdata, idx = [], [], 0
    skipped = 0
    for s in syms:
        n = s['name']
        if s['ndx'] == 'ABS' or n in node_names: continue
        if (s['ver'] is None or s['dflt']) and n in exclude: skipped += 1; continue
        idx += 1
        label = n if s['dflt'] else '__stubh_%d' % idx
        lines = []
        if s['dflt']:
            lines.append('\t.globl %s' % asm_name(label))
            if s['bind'] == 'WEAK': lines[-1] = '\t.weak %s' % asm_name(label)
            if s['vis'] == 'PROTECTED': lines.append('\t.protected %s' % asm_name(label))
            if s['ver']: script[s['ver']].append(n)
        else:
            lines.append('\t.globl %s\n\t.hidden %s' % (label, label))
            lines.append('\t.symver %s, %s@%s' % (label, asm_name(n), s['ver']))
        mapping.append((idx, n, s['ver'] or '', s['type'], s['size']))
        if s['type'] in ('FUNC', 'IFUNC', 'NOTYPE'):
            lines.append('\t.type %s, @function' % asm_name(label))
            lines.append('%s:' % asm_name(label))
            if n in RET_EMPTY_STR:
                lines.append('\tleaq __stub_empty(%rip), %rax\n\tret')
            else:
                lines.append('\tmovl $%d, %%edi\n\tjmp __stub_called' % idx)
            S.extend(lines)
        elif s['type'] == 'TLS':
            lines.append('\t.type %s, @tls_object\n\t.size %s, %d\n%s:\n\t.zero %d' % (asm_name(label), asm_name(label), s['size'], asm_name(label), max(s['size'], 1)))
            tdata.extend(lines)
        else:  # OBJECT, COMMON
            t = '@gnu_unique_object' if s['bind'] == 'UNIQUE' else '@object'
            lines.append('\t.type %s, %s\n\t.size %s, %d\n%s:\n\t.zero %d' % (asm_name(label), t, asm_name(label), s['size'], asm_name(label), max(s['size'], 1)))
            data.extend(lines)
    if data: S += ['\t.bss', '\t.balign 64'] + ['\t.balign 16\n' + l if l.startswith('\t.globl') or l.startswith('\t.weak') else l for l in data]
    if tdata: S += ['\t.section .tbss,"awT",@nobits', '\t.balign 16'] + tdata
    S.append('\t.section .note.GNU-stack,"",@progbits')
    os.makedirs(outdir, exist_ok=True)
    sfile = os.path.join(outdir, base + '.S'); open(sfile, 'w').write('\n'.join(S) + '\n')
    cfile = os.path.join(outdir, base + '_h.c')
    open(cfile, 'w').write('''#include <stdio.h>
#include <stdlib.h>
__attribute__((visibility("hidden"))) const char __stub_empty[64] = {0};
__attribute__((visibility("hidden"))) long __stub_called(long idx) {
  static int mode = -1, n = 0;
  if (mode < 0) { const char* e = getenv("STUB_TRACE"); mode = e && *e == '1'; }
  if (mode && n < 200) { n++; fprintf(stderr, "[stub] %s #%%ld\\n", idx); }
  return 0;
}
''' % soname)
    cmd = ['gcc', '-shared', '-fPIC', '-O1', '-o', os.path.join(outdir, soname), sfile, cfile, '-Wl,-soname,' + soname, '-Wl,--no-undefined', '-Wl,-z,noexecstack', '-s']
    if nodes:
        vs = os.path.join(outdir, base + '.ver')
        with open(vs, 'w') as f:
            for n, parents in nodes:
                syms_ = script[n]
                body = ('global:\n' + ''.join('  %s;\n' % x.replace('"', '\\"') if False else '  "%s";\n' % x for x in syms_)) if syms_ else ''
                f.write('%s {\n%s}%s;\n' % (n, body, (' ' + ' '.join(parents)) if parents else ''))
        cmd.append('-Wl,--version-script=' + vs)
    subprocess.run(cmd, check=True)
    with open(os.path.join(outdir, base + '.map'), 'w') as f:
        for m in mapping: f.write('%d %s %s %s %d\n' % m)
    return idx, skipped

if __name__ == '__main__':
    stubs = sys.argv[1].split(',')
    outdir = sys.argv[2]
    roots = sys.argv[3].split(',')
    real = [n for n in closure(roots, set(stubs)) if n not in stubs]
    exclude = set()
    for n in real:
        p = os.path.join(LIB, n)
        if os.path.exists(p):
            exclude |= {s['name'] for s in dynsyms(p)}
    for p in SYSLIBS + ['/lib/x86_64-linux-gnu/libstdc++.so.6', '/lib/x86_64-linux-gnu/libgcc_s.so.1']:
        exclude |= {s['name'] for s in dynsyms(p)}
    for s in stubs:
        k, sk = gen(s, outdir, exclude)
        print('%-28s %6d symbols, %5d left to kept libs, %8d bytes' % (s, k, sk, os.path.getsize(os.path.join(outdir, s))))
