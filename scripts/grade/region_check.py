"""region_check.py — what a student's exercise region may hold (docs/solutions.md, "What a region may
hold"). A region is the body of one exercise: plain C++ or GLSL statements inside the function that
holds it. The grader gives 0, with the reason, to a region that steps outside that:

  * it closes its function: its braces do not balance (a `}` closes more than the region opened, or
    the region ends inside a block it opened), or it spells a brace as a digraph (`<%`, `%>`);
  * it holds a preprocessor line (`#`, `%:`, `_Pragma`) or a line that ends in a backslash;
  * it calls output, process, file, signal, jump or dynamic-loading functions, reads the environment,
    uses inline assembly, a compiler builtin or an identifier reserved to the implementation (`__x`),
    declares something `extern`, or names the test side: the reference (`ref::`), the probe
    (`lab_probe`), GoogleTest (`testing`).

None of these is needed by any exercise; each is how a region could reach past its function to the
verdict. The check reads the region's tokens after removing comments and string and character
literals (raw strings are refused: their end cannot be told without the compiler).
"""
import re

# Calls: a name followed by `(`.
CALLS = {
    # output
    "printf", "fprintf", "vprintf", "vfprintf", "dprintf", "puts", "fputs", "putchar", "fputc", "putc", "fwrite",
    "write", "writev", "pwrite", "perror", "fflush", "print", "println",
    # files
    "fopen", "freopen", "fdopen", "open", "openat", "creat", "read", "pread", "fread", "fgets", "getline", "remove",
    "rename", "unlink", "truncate", "ftruncate", "mkdir", "chmod", "symlink", "link", "tmpfile", "close", "dup", "dup2",
    "mmap", "mprotect", "munmap", "ioctl", "fcntl", "opendir", "readdir",
    # processes and the environment
    "system", "popen", "fork", "vfork", "clone", "execl", "execlp", "execle", "execv", "execvp", "execve", "execvpe",
    "posix_spawn", "posix_spawnp", "kill", "raise", "abort", "exit", "_exit", "_Exit", "quick_exit", "atexit",
    "at_quick_exit", "terminate", "set_terminate", "getenv", "secure_getenv", "setenv", "putenv", "unsetenv",
    "syscall", "ptrace", "process_vm_writev", "prctl", "pthread_create", "sleep", "usleep", "nanosleep",
    # jumps and signals
    "setjmp", "longjmp", "_setjmp", "_longjmp", "sigsetjmp", "siglongjmp", "signal", "sigaction", "sigprocmask",
    "alarm", "setitimer",
    # dynamic loading
    "dlopen", "dlsym", "dlvsym", "dlclose", "dladdr",
}
# Names refused wherever they stand: streams, files, threads, the test side.
NAMES = {
    "cout", "cerr", "clog", "cin", "wcout", "wcerr", "stdout", "stderr", "stdin", "FILE", "ofstream", "ifstream",
    "fstream", "filebuf", "ostream", "istream", "iostream", "ostringstream", "filesystem", "thread", "jthread",
    "async", "asm", "extern", "_Pragma", "ref", "lab_probe", "testing", "gtest",
}

_TOKEN = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def _strip(text):
    """(code without comments and literals, reason or None). Literals become "" / '' so that lines and
    tokens stay where they were."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            if j < 0:
                return None, "a comment that does not end inside the region"
            out.append("\n" * text.count("\n", i, j))
            i = j + 2
        elif c in "\"'":
            if c == '"' and i > 0 and text[i - 1] == "R":
                return None, "a raw string literal"
            j = i + 1
            while j < n and text[j] != c:
                if text[j] == "\n":
                    return None, "a string or character literal that does not end on its line"
                j += 2 if text[j] == "\\" else 1
            if j >= n:
                return None, "a string or character literal that does not end"
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out), None


def problems(body, language="cpp"):
    """The reasons region text `body` may not be graded (an empty list: it may)."""
    found = []
    code, why = _strip(body)
    if why:
        return [why]
    for k, line in enumerate(code.splitlines(), 1):
        s = line.strip()
        if s.startswith("#") or s.startswith("%:"):
            found.append(f"a preprocessor line (line {k} of the region)")
        if line.rstrip().endswith("\\"):
            found.append(f"a line that ends in a backslash (line {k} of the region)")
        if "??" in line:
            found.append(f"a trigraph (line {k} of the region)")
    if "<%" in code or "%>" in code or "%:" in code:
        found.append("a digraph for a brace or #")
    depth = 0
    for c in code:
        if c == "{":
            depth += 1
        elif c == "}":
            depth -= 1
            if depth < 0:
                break
    if depth != 0:
        found.append("closes its function (its braces do not balance)")
    calls, names, reserved = [], [], []
    for m in _TOKEN.finditer(code):
        name = m.group(0)
        rest = code[m.end():].lstrip()
        before = code[:m.start()].rstrip()
        if name.startswith("__"):
            reserved.append(name)
        elif name in ("ref", "testing"):
            if rest.startswith("::") or before.endswith("namespace"):
                names.append(name)
        elif name in NAMES:
            names.append(name)
        elif name in CALLS and rest.startswith("("):
            calls.append(name)
    unique = lambda xs: ", ".join(dict.fromkeys(xs))
    if calls:
        found.append(f"calls {unique(calls)} (output, files, processes, signals, jumps or dynamic loading)")
    if names:
        found.append(f"uses {unique(names)} (streams, files, threads, assembly, extern, or the test side)")
    if reserved:
        found.append(f"uses {unique(reserved)} (reserved to the compiler: builtins, attributes, assembly)")
    return found
