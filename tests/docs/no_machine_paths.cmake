# cmake -DROOT=<repository> -P no_machine_paths.cmake
# Fails, naming file and line, where README.md or anything under docs/ holds an absolute
# path of a machine (/home, /root, /tmp, /work, /usr/local/...): generated text names
# paths relative to the repository.
file(GLOB_RECURSE files ${ROOT}/docs/*.md ${ROOT}/docs/*.jsonl ${ROOT}/docs/*.json ${ROOT}/docs/*.txt)
list(APPEND files ${ROOT}/README.md)
set(found "")
foreach(file ${files})
    file(STRINGS ${file} lines REGEX "(^|[^A-Za-z0-9_.~-])/(home|root|tmp|work|mnt|Users)/")
    foreach(line ${lines})
        file(RELATIVE_PATH name ${ROOT} ${file})
        string(SUBSTRING "${line}" 0 160 line)
        string(APPEND found "\n  ${name}: ${line}")
    endforeach()
endforeach()
if(found)
    message(FATAL_ERROR "absolute machine paths in the documents:${found}")
endif()
