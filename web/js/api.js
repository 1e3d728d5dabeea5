// Every API call the pages make: where the server requires keys (serve --api-keys) it answers
// 401, and the page asks for the student's key once. Where students need none
// (serve --students-without-keys), a TA enters their staff key with the header's button.
//
// The key is handed to the server once (POST /api/session), which keeps it in an HttpOnly,
// SameSite=Strict cookie: no script on this page can read it back, so none can carry it off.
// Earlier pages kept it in localStorage: a key found there is moved into the cookie and removed.
const kLegacyKey = "shadelab.apiKey";

// Enters `key` for this browser; true when the server took it.
async function enterKey(key) {
  const response = await fetch("/api/session", { method: "POST", headers: { Authorization: `Bearer ${key}` } });
  return response.ok;
}

const legacyMoved = (async () => {
  const legacy = localStorage.getItem(kLegacyKey);
  if (!legacy) return;
  localStorage.removeItem(kLegacyKey);
  await enterKey(legacy);
})();

export async function api(path, init = {}) {
  await legacyMoved;
  for (let attempt = 0; ; attempt++) {
    const response = await fetch(path, init);
    if (response.status !== 401 || attempt > 0) return response;
    const entered = window.prompt("This ShadeLab server needs your course API key:");
    if (!entered?.trim() || !(await enterKey(entered.trim()))) return response;
  }
}

// The header's button: enter a key (a TA's staff key), or forget the one this browser holds. The
// page opens again so that what it lists is what the key may see.
export async function offerKey(button) {
  await legacyMoved;
  const session = await (await fetch("/api/session")).json().catch(() => ({ keyEntered: false }));
  button.textContent = session.keyEntered ? "Key entered (forget it)" : "Staff key";
  button.addEventListener("click", async () => {
    if (session.keyEntered) {
      await fetch("/api/session/end", { method: "POST" });
    } else {
      const entered = window.prompt("Your staff key (TAs; students need none here):");
      if (!entered?.trim() || !(await enterKey(entered.trim()))) return;
    }
    window.location.reload();
  });
}

// A problem+json answer's words, or the status line.
export async function problemText(response) {
  const text = await response.text();
  try {
    const p = JSON.parse(text);
    return p.detail ?? p.title ?? text;
  } catch {
    return `${response.status} ${response.statusText}`;
  }
}
