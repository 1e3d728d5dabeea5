#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora (tests/fuzz/corpus/<target>/) from the repository's real
inputs: the presets' shader modules, the scene shaders, the example scenes, the built-in meshes'
formats and the requests the API documents. A maintainer's tool: the seeds are committed, and
neither the build nor the tests run this. wire_message's seeds come from the service's own
encoder (the fuzz_wire_seeds program); run it after this."""
import base64, glob, json, os, struct, sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CORPUS = os.path.join(ROOT, "tests", "fuzz", "corpus")
SEP = b"\n--8<--\n"


def write(target, name, data):
    d = os.path.join(CORPUS, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def read(path):
    with open(os.path.join(ROOT, path), "rb") as f:
        return f.read()


def shader_seeds():
    modules = sorted(glob.glob(os.path.join(ROOT, "shaders", "*.js")))
    for path in modules:
        name = os.path.basename(path)
        selector = b"\x03" if "frag" in name else b"\x02"
        write("shader_source", name, selector + read(path))
    for path in sorted(glob.glob(os.path.join(ROOT, "shaders", "scene", "*"))):
        name = os.path.basename(path)
        write("shader_source", name, (b"\x01" if name.endswith(".frag") else b"\x00") + read(path))
    write("shader_source", "crlf_bom_template.js",
          b"\x03\xef\xbb\xbfexport default `#version 300 es\r\nprecision highp float;\r\nout vec4 c;\r\n"
          b"void main() { c = vec4(${1 + 1}); }\r\n`;\r\n")
    write("shader_source", "quoted_string.js",
          b"\x03export default \"#version 300 es\\nprecision highp float;\\nout vec4 c;\\nvoid main() { c = vec4(1); }\\n\";\n")
    frag = read("shaders/specular_frag.js")
    logs = [
        b"0:3(3): error: `x' undeclared\n0:3(3): warning: statement has no effect\n",
        b"0(7) : error C1008: undefined variable \"x\"\n",
        b"ERROR: 0:7: 'x' : undeclared identifier\nERROR: 1 compilation errors.  No code generated.\n",
        b"error: fragment shader output `c' has no location\n  continued on a second line\n",
        b"0:12(5): preprocessor error: syntax error, unexpected NEWLINE\n",
    ]
    for k, log in enumerate(logs):
        write("driver_log", "log_%d" % k, bytes([k & 1]) + frag + SEP + log)


def scene_seeds():
    for path in sorted(glob.glob(os.path.join(ROOT, "assets", "scenes", "*.json"))):
        write("scene_description", os.path.basename(path), read(path))
    full = {
        "objects": [{"name": "Suzanne", "mesh": "suzanne", "location": [0, 0, 1], "rotation": [0, 0, 45], "scale": [1, 2, 1],
                     "shading": "flat", "material": {"baseColor": [0.8, 0.1, 0.1], "metallic": 1, "roughness": 0.2,
                                                     "subsurface": 0.1, "emission": [0, 0, 0], "alpha": 1}}],
        "ground": {"size": 20, "height": 0},
        "camera": {"location": [7, -7, 5], "rotation": [60, 0, 45], "lens": 35, "sensorFit": "horizontal", "clipStart": 0.1, "clipEnd": 100},
        "lights": [{"type": "sun", "strength": 3, "rotation": [30, 0, 0]}, {"type": "spot", "spotSize": 30, "spotBlend": 0.2, "location": [0, 0, 5], "power": 500},
                   {"type": "area", "location": [0, 2, 4], "size": 2}],
        "world": {"color": [0.05, 0.05, 0.05], "strength": 1},
        "render": {"width": 320, "height": 240, "engine": "workbench", "viewTransform": "standard", "samples": 0},
    }
    write("scene_description", "every_section.json", json.dumps(full))


def mesh_seeds():
    tri = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
    write("mesh_loader", "cube.obj", b"\x00" + b"".join(b"v %d %d %d\n" % (x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1))
          + b"vn 0 0 1\nf 1//1 2//1 4//1 3//1\nf 5 6 8 7\nl 1 2\np 3\ng part\nf 1 5 6 2\n")
    write("mesh_loader", "teapot_head.obj", b"\x00" + b"\n".join(read("assets/teapot.obj").split(b"\n")[:400]))
    write("mesh_loader", "triangle_ascii.ply", b"\x01" + b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
          b"property float z\nproperty float nx\nproperty float ny\nproperty float nz\nelement face 1\n"
          b"property list uchar int vertex_indices\nend_header\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n")
    binary = b"".join(struct.pack("<3f", *p) for p in tri) + struct.pack("<B3i", 3, 0, 1, 2)
    write("mesh_loader", "triangle_binary.ply", b"\x01" + b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
          b"property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n" + binary)
    write("mesh_loader", "triangle_ascii.stl", b"\x02" + b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
          b"vertex 0 1 0\nendloop\nendfacet\nendsolid t\n")
    stl = b"\0" * 80 + struct.pack("<I", 1) + struct.pack("<12fH", 0, 0, 1, *[c for p in tri for c in p], 0)
    write("mesh_loader", "triangle_binary.stl", b"\x02" + stl)
    positions = b"".join(struct.pack("<3f", *p) for p in tri)
    indices = struct.pack("<3H", 0, 1, 2) + b"\0\0"
    buffer = positions + indices
    gltf = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
            "nodes": [{"children": [1], "scale": [2, 2, 2]}, {"mesh": 0, "translation": [0, 2, 0], "rotation": [0, 0.7071, 0, 0.7071]}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
            "buffers": [{"byteLength": len(buffer), "uri": "data:application/octet-stream;base64," + base64.b64encode(buffer).decode()}],
            "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                          {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]}
    write("mesh_loader", "triangle.gltf", b"\x03" + json.dumps(gltf).encode())
    glb_json = dict(gltf)
    glb_json["buffers"] = [{"byteLength": len(buffer)}]
    text = json.dumps(glb_json).encode()
    text += b" " * (-len(text) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(buffer), 0x004E4942) + buffer
    write("mesh_loader", "triangle.glb", b"\x04" + struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks)


def request_seeds():
    frag = read("shaders/specular_frag.js")
    vert = read("shaders/specular_vert.js")
    bodies = {
        "render_preset.json": (0, {"preset": "specular", "mesh": "bunny", "frames": 3, "width": 64, "height": 48}),
        "render_sources.json": (0, {"vertex": vert.decode(), "fragment": frag.decode(), "mesh": "teapot", "msaa": 0,
                                     "uniforms": {"uLightDirection": [1, 1, 1], "uShininess": 20}, "output": "frames", "format": "exr"}),
        "compile.json": (1, {"preset": "normals"}),
        "grade_checkpoint.json": (2, {"preset": "diffuse", "reference": "diffuse", "threshold": 4, "maxFailingFraction": 0.01,
                                       "spatialTolerance": 1, "maxScore": 10, "format": "gradescope"}),
        "grade_custom.json": (2, {"vertex": vert.decode(), "fragment": frag.decode(), "referenceVertex": vert.decode(),
                                   "referenceFragment": frag.decode()}),
        # Saved frames: two named, one a stray, the code beside them (the PNG bytes need not decode here).
        "grade_frames.json": (3, {"reference": "specular", "vertex": vert.decode(), "fragment": frag.decode(),
                                   "savedFrames": [{"name": "hw2_specular_1.png", "png": "iVBORw0KGgo="},
                                                   {"name": "hw2_specular_0.png", "png": "iVBORw0KGgo="},
                                                   {"name": "notes.txt", "png": ""}]}),
    }
    for name, (selector, body) in bodies.items():
        write("api_json", name, bytes([selector]) + json.dumps(body).encode())
    # Nesting just past the client JSON budget (core/client_json.h: 32 levels), where a body once
    # nested 200,000 arrays deep and crashed the server when an error dumped it.
    deep = "[" * 33 + "]" * 33
    write("api_json", "deep_frames.json", b"\x03" + ('{"reference": "specular", "savedFrames": %s}' % deep).encode())
    write("api_json", "deep_width.json", b"\x00" + ('{"preset": "starter", "width": %s}' % deep).encode())

    def http(method, target, headers, body=b""):
        head = "%s %s HTTP/1.1\r\nHost: localhost\r\n" % (method, target)
        for k, v in headers:
            head += "%s: %s\r\n" % (k, v)
        if body and not any(k.lower() == "transfer-encoding" for k, _ in headers):
            head += "Content-Length: %d\r\n" % len(body)
        return head.encode() + b"\r\n" + body

    json_body = json.dumps(bodies["render_preset.json"][1]).encode()
    write("http_request", "get_render", http("GET", "/api/render?preset=smooth&mesh=teapot&frames=2&width=32&height=24&uniforms=%7B%7D", []))
    write("http_request", "post_json", http("POST", "/api/render", [("Content-Type", "application/json")], json_body))
    write("http_request", "post_compile", http("POST", "/api/compile", [("Content-Type", "application/json")], b'{"preset":"smooth"}'))
    write("http_request", "post_grade", http("POST", "/api/grade", [("Content-Type", "application/json")],
                                             json.dumps(bodies["grade_checkpoint.json"][1]).encode()))
    write("http_request", "post_urlencoded", http("POST", "/api/render", [("Content-Type", "application/x-www-form-urlencoded")],
                                                  b"preset=diffuse&frames=1&msaa=0&fit=true"))
    boundary = "shadelabBoundary"
    parts = [("preset", None, b"specular"), ("frames", None, b"2"), ("vertex", "phong_vert.js", vert), ("fragment", "phong_frag.js", frag),
             ("mesh", "tri.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")]
    multipart = b""
    for name, filename, content in parts:
        disposition = 'form-data; name="%s"' % name + ('; filename="%s"' % filename if filename else "")
        multipart += b"--" + boundary.encode() + b"\r\nContent-Disposition: " + disposition.encode() + b"\r\n\r\n" + content + b"\r\n"
    multipart += b"--" + boundary.encode() + b"--\r\n"
    write("http_request", "post_multipart", http("POST", "/api/render", [("Content-Type", "multipart/form-data; boundary=" + boundary)], multipart))
    scene = read("assets/scenes/two_objects.json")
    write("http_request", "post_scene", http("POST", "/api/scene", [("Content-Type", "application/json"), ("Accept", "application/json")], scene))
    scene_multipart = (b"--b\r\nContent-Disposition: form-data; name=\"scene\"; filename=\"scene.json\"\r\n\r\n" +
                       b'{"objects":[{"mesh":"tri"}]}' + b"\r\n--b\r\nContent-Disposition: form-data; name=\"tri\"; filename=\"tri.obj\"\r\n\r\n"
                       b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n\r\n--b--\r\n")
    write("http_request", "post_scene_multipart", http("POST", "/api/scene", [("Content-Type", "multipart/form-data; boundary=b")], scene_multipart))
    chunked = b"13\r\n" + b'{"preset":"smooth",' + b"\r\n" + b"c\r\n" + b'"frames": 1}' + b"\r\n0\r\n\r\n"
    write("http_request", "post_chunked", http("POST", "/api/render", [("Content-Type", "application/json"), ("Transfer-Encoding", "chunked")], chunked))
    write("http_request", "expect_continue", http("POST", "/api/compile", [("Content-Type", "application/json"), ("Expect", "100-continue")],
                                                  b'{"preset":"specular"}'))

    fields = {
        "forwarded_for": b"\x00" + b"127.0.0.1" + SEP + b"203.0.113.7, 10.1.2.3" + SEP + b"192.168.0.0/16",
        "forwarded_for_v6": b"\x00" + b"::1" + SEP + b"2001:db8::1 , ::1" + SEP + b"::1/128",
        "proxy_range": b"\x01" + b"10.0.0.0/8" + SEP + b"10.200.3.4",
        "proxy_range_v6": b"\x01" + b"fd00::/8" + SEP + b"fd12::1",
        "redis_url": b"\x02redis://cache.internal:6380/2",
        "redis_unix": b"\x02unix:///run/shadelab/redis.sock",
        "redis_host_port": b"\x02127.0.0.1:6379",
        "number_list": b"\x03\x06" + b"1,2.5,-3",
        "number_list_booleans": b"\x03\x01" + b"true,false,1e3",
    }
    for name, data in fields.items():
        write("request_fields", name, data)


def png(width, height, colour_type, depth, rows, palette=None):
    """A PNG written by hand: the encodings a browser or an image tool may hand in."""
    import zlib
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + r for r in rows)
    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, depth, colour_type, 0, 0, 0))
    if palette:
        out += chunk(b"PLTE", palette)
    return out + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


def png_seeds():
    rgba = png(4, 3, 6, 8, [b"".join(bytes([x * 60, y * 80, 128, 255]) for x in range(4)) for y in range(3)])
    write("saved_png", "rgba8.png", rgba)
    write("saved_png", "rgb8.png", png(3, 2, 2, 8, [bytes([10, 20, 30] * 3), bytes([200, 100, 0] * 3)]))
    write("saved_png", "grey16.png", png(2, 2, 0, 16, [b"\x12\x34\xff\xff", b"\x00\x00\x80\x00"]))
    write("saved_png", "palette.png", png(4, 1, 3, 8, [bytes([0, 1, 2, 1])], palette=bytes([0, 0, 0, 255, 0, 0, 0, 0, 255])))
    write("saved_png", "truncated.png", rgba[: len(rgba) // 2])
    write("saved_png", "too_wide.png", png(100000, 1, 0, 8, [b"\x00"]))
    # A header that claims 4096 x 4096 (a sheet's pixel budget is summed from such headers) with
    # one row of data: refused by its size before any decoder allocates.
    write("saved_png", "claims_4096.png", png(4096, 4096, 0, 8, [b"\x00" * 4096]))


if __name__ == "__main__":
    shader_seeds()
    scene_seeds()
    mesh_seeds()
    request_seeds()
    png_seeds()
    print("seeds written under", CORPUS, file=sys.stderr)
