// Every API call the pages make: where the server requires keys (serve --api-keys) it answers
// 401, and the page asks for the student's key once and keeps it in this browser.
export async function api(path, init = {}) {
  for (let attempt = 0; ; attempt++) {
    const key = localStorage.getItem("shadelab.apiKey");
    const headers = { ...(init.headers ?? {}), ...(key ? { Authorization: `Bearer ${key}` } : {}) };
    const response = await fetch(path, { ...init, headers });
    if (response.status !== 401 || attempt > 0) return response;
    const entered = window.prompt("This ShadeLab server needs your course API key:");
    if (!entered) return response;
    localStorage.setItem("shadelab.apiKey", entered.trim());
  }
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
