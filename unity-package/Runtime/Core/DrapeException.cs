using System;

namespace Drape.Core
{
    /// <summary>A Drape call failed. <see cref="NativeMessage"/> is drape_last_error()'s text.</summary>
    public sealed class DrapeException : Exception
    {
        public DrapeException(Status status, string function, string nativeMessage)
            : base(function + " failed with " + status + ": " + nativeMessage)
        {
            Status = status;
            Function = function;
            NativeMessage = nativeMessage;
        }

        /// <summary>The status the native call returned.</summary>
        public Status Status { get; }

        /// <summary>The C function that failed, e.g. "drape_cloth_step".</summary>
        public string Function { get; }

        /// <summary>The native library's message for this failure.</summary>
        public string NativeMessage { get; }
    }
}
