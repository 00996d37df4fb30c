"""A doc's fenced block as commands and the output lines they must print (used by doc_walkthrough.py and
doc_commands.py).

In a block, a line starting with one of `starts` begins a command (continued by lines ending in a
backslash) unless `is_command` says otherwise; every other non-empty line is output that one of the
block's commands must print, verbatim; `...` lines stand for lines left out.
"""


def commands_and_expected(block, starts, is_command=lambda line: True):
    commands, expected = [], []
    lines = block.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith(starts) and is_command(line):
            command = line
            while command.endswith("\\"):
                i += 1
                command = command[:-1] + " " + lines[i].strip()
            commands.append(command)
        elif line.strip() and line.strip() != "...":
            expected.append(line.rstrip())
        i += 1
    return commands, expected
