// Every API call the pages make: where the server requires keys (serve --api-keys) it answers
// 401, and the page asks for the student's key once and keeps it in this browser. Where students
// need none (serve --students-without-keys), a TA enters their staff key with the header's button.
const kKey = "shadelab.apiKey";

export async function api(path, init = {}) {
  for (let attempt = 0; ; attempt++) {
    const key = localStorage.getItem(kKey);
    const headers = { ...(init.headers ?? {}), ...(key ? { Authorization: `Bearer ${key}` } : {}) };
    const response = await fetch(path, { ...init, headers });
    if (response.status !== 401 || attempt > 0) return response;
    const entered = window.prompt("This ShadeLab server needs your course API key:");
    if (!entered) return response;
    localStorage.setItem(kKey, entered.trim());
  }
}

// The header's button: enter a key (a TA's staff key), or forget the one this browser keeps. The
// page opens again so that what it lists is what the key may see.
export function offerKey(button) {
  const show = () => {
    button.textContent = localStorage.getItem(kKey) ? "Key entered (forget it)" : "Staff key";
  };
  show();
  button.addEventListener("click", () => {
    if (localStorage.getItem(kKey)) {
      localStorage.removeItem(kKey);
    } else {
      const entered = window.prompt("Your staff key (TAs; students need none here):");
      if (!entered?.trim()) return;
      localStorage.setItem(kKey, entered.trim());
    }
    show();
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
